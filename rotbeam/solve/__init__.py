"""Numerics that turn the model into a periodic steady state: spectral helpers, trigonometric
collocation, TR-BDF2 and the time stepping to a verified steady state."""
