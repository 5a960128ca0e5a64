"""What exists only to reproduce or judge the paper (no core module imports it)."""
