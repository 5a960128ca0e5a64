"""What the runs say: critical frequencies and fits of the boundary, and the engineer's verdict."""
