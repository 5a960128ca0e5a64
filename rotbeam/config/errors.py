"""The one error a user sees for bad input: `RotbeamInputError`, one line naming the value and
what is allowed (the command line turns it into exit status 2)."""


class RotbeamInputError(ValueError):
    """A user-supplied value is outside its allowed range; the message names value and range."""
