"""The work-precision benchmark: its plan, its runs and its report."""
