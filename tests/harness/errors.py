"""The refusal contract of every public function: a bad value raises
:class:`symhx.validation.InputError` (a ``ValueError``; a wrong kind of object ``TypeError``) whose
message names the argument, shows the offending value and says
what is allowed.  Tests check those three parts, not the whole sentence.

>>> import symhx
>>> msg = assert_refuses(symhx.phi, 0, 1, arg="N", value="0", allowed=">= 1")
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from typing import Any

import pytest

from symhx.validation import InputError

__all__ = ["assert_refuses"]


def assert_refuses(fn: Callable[..., Any], *args: Any, exc: type[BaseException] = InputError,
                   arg: str | Iterable[str], value: str | None = None,
                   allowed: str | Iterable[str] | None = None, **kwargs: Any) -> str:
    """Call ``fn(*args, **kwargs)``, require ``exc`` and return its message.

    ``arg``: the argument name(s) the message must name (as a word); ``value``: a text the
    message must contain (how the offending value is shown); ``allowed``: text(s) describing what
    is allowed (a bound, a range, a type).  Each is matched as a literal substring (the argument
    name as a whole word), so the wording around them may change freely.
    """
    with pytest.raises(exc) as info:
        fn(*args, **kwargs)
    msg = str(info.value)
    for name in [arg] if isinstance(arg, str) else list(arg):
        assert re.search(rf"(?<![\w.]){re.escape(name)}(?!\w)", msg), \
            f"message does not name the argument {name!r}: {msg!r}"
    if value is not None:
        assert value in msg, f"message does not show the value {value!r}: {msg!r}"
    for text in [] if allowed is None else ([allowed] if isinstance(allowed, str) else allowed):
        assert text in msg, f"message does not say what is allowed ({text!r}): {msg!r}"
    return msg
