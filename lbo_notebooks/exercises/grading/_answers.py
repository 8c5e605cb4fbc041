"""Reading answers the way several graders do: numbers and choices as the checks expect them, and
recaps of choices (nb09, nb10)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..feedback import WRONG, Stop, as_number, is_placeholder
from ._registry import Verdict, recap_verdict



def number(answer: Any, what: str) -> Any:
    """The answer as the checks read it: placeholders stay (the check says "not attempted"), anything
    that is no number becomes a wrong answer with a clear message instead of an exception."""
    if is_placeholder(answer):
        return answer
    try:
        return as_number(answer, what)
    except Stop:
        raise
    except Exception:  # noqa: BLE001 - an answer object whose conversion itself fails
        raise Stop(WRONG, f"Expected {what}, got {type(answer).__name__}.") from None


def choice(answer: Any) -> Any:
    """A choice answer with its spaces normalised ("Less  than half " -> "less than half");
    anything else as given (the check names the options)."""
    if isinstance(answer, str) and not is_placeholder(answer):
        return " ".join(answer.split()).lower()
    return answer


def recap_of_choices(answers: list[Any], judges: list[Callable[[Any], str | None]]) -> Verdict:
    """A recap's partial credit (``_registry.recap_verdict``), each answer read like a choice first
    (case and spaces ignored)."""
    return recap_verdict(answers, [lambda answer, judge=judge: judge(choice(answer)) for judge in judges])
