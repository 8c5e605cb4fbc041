"""docs/maintainers.md states facts about determinism, caching and the recorded benchmarks; its
Python blocks assert them. This runs the blocks, in order and in one namespace, as the page says
a maintainer would (from the repository root), so that a new recording or a changed default that
falsifies a sentence of the page fails here."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
PAGE = REPO / "docs" / "maintainers.md"
BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def test_the_page_has_its_checks():
    blocks = BLOCK.findall(PAGE.read_text(encoding="utf-8"))
    assert sum("assert" in b for b in blocks) >= 5, "the page's checks (Python blocks with asserts) went missing"


def test_every_block_of_the_page_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(REPO)  # the page's blocks read benchmarks/... from the repository root
    namespace: dict = {"__name__": "maintainers_page"}
    for number, block in enumerate(BLOCK.findall(PAGE.read_text(encoding="utf-8")), start=1):
        try:
            exec(compile(block, f"{PAGE.name}, Python block {number}", "exec"), namespace)  # noqa: S102 - the page's own code
        except Exception as error:  # noqa: BLE001 - report which block, with its error
            pytest.fail(f"{PAGE.relative_to(REPO)}, Python block {number}: {type(error).__name__}: {error}")
