"""Runs of the full model: one scene (dynamic beside quasi-static), a sweep line, and the
workflow's studies built from its config."""
