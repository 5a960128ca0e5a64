"""Output: one plotting style, the paper's figures and tables, and one atomic writer."""
