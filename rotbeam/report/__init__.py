"""Output: one plotting style, one atomic writer, the workflow jobs' log, and the figures of the
commands and of the nonlinear target (the paper's own figures are in `rotbeam.paper`)."""
