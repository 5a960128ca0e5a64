"""The one error a user sees for bad input: `RotbeamInputError`, one line naming the value and
what is allowed (the command line turns it into exit status 2)."""

from __future__ import annotations


def one_line(text: str) -> str:
    """`text` on one line: characters that are not printable (line breaks, control characters
    from a malformed file) written as their escapes.

    Parameters
    ----------
    text : str
        A message.

    Returns
    -------
    str
        The message with every non-printable character escaped, e.g. "\\n", "\\x1e".
    """
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)


class RotbeamInputError(ValueError):
    """A user-supplied value is outside its allowed range; the message names value and range,
    on one line whatever the value holds (`one_line`)."""

    def __init__(self, message: object = "") -> None:
        super().__init__(one_line(str(message)))
