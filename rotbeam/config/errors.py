"""The one error a user sees for bad input."""


class RotbeamInputError(ValueError):
    """A user-supplied value is outside its allowed range; the message names value and range."""
