"""User input: the one error type, the number checks, the parameter registry (type, default,
range and help of every beam, drive, effects and numerics field) and YAML reading.

The bottom layer: it imports nothing else from rotbeam, so every other room may use it."""
