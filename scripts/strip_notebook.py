#!/usr/bin/env python3
"""Git clean filter: a notebook as it is committed, i.e. without what running it adds.

JupyterLab's autosave writes outputs, execution counts, widget state and the kernel's full
``language_info`` into the notebook file, so a course member who ran a notebook cannot
``git pull`` without a conflict. ``make.sh`` registers this script as the clean filter of
``*.ipynb`` (see ``.gitattributes``): git then stores and compares notebooks as if they had
just been cleared, and the file on disk keeps its outputs. A notebook that is already clean
comes out byte for byte as it went in (nbformat's layout: sorted keys, one-space indent).
Standard library only, so that it runs with any ``python3``.

    python3 scripts/strip_notebook.py < notebook.ipynb > clean.ipynb
"""

from __future__ import annotations

import json
import sys

# Cell metadata that only records how a run looked; "jupyter.source_hidden" (collapsed
# solutions) is part of the course and is kept.
_RUN_STATE = ("collapsed", "scrolled", "execution", "ExecuteTime")


def strip(nb: dict) -> dict:
    """Return ``nb`` without outputs, execution counts, widget state or kernel version details.

    Examples
    --------
    >>> cell = {"cell_type": "code", "execution_count": 3, "metadata": {"scrolled": True},
    ...         "outputs": [{"output_type": "stream", "name": "stdout", "text": ["hi"]}], "source": []}
    >>> nb = {"cells": [cell], "metadata": {"language_info": {"name": "python", "version": "3.11.7"}}}
    >>> out = strip(nb)
    >>> out["cells"][0]["outputs"], out["cells"][0]["execution_count"], out["cells"][0]["metadata"]
    ([], None, {})
    >>> out["metadata"], nb["cells"][0]["execution_count"]
    ({'language_info': {'name': 'python'}}, 3)
    """
    nb = json.loads(json.dumps(nb))  # a copy: never modify the caller's notebook
    meta = nb.get("metadata", {})
    meta.pop("widgets", None)
    # the kernel fills in its version on every run; the committed notebook names the language only
    language = meta.get("language_info", {}).get("name") or meta.get("kernelspec", {}).get("language", "python")
    meta["language_info"] = {"name": language}
    for cell in nb.get("cells", []):
        cmeta = cell.get("metadata", {})
        for key in _RUN_STATE:
            cmeta.pop(key, None)
        jupyter = cmeta.get("jupyter")
        if isinstance(jupyter, dict):
            jupyter.pop("outputs_hidden", None)
            if not jupyter:
                del cmeta["jupyter"]
        if cell.get("cell_type") == "code":
            cell["outputs"] = []
            cell["execution_count"] = None
    return nb


def main() -> None:
    text = sys.stdin.buffer.read().decode("utf-8")
    try:
        nb = json.loads(text)
    except ValueError:  # not JSON (e.g. conflict markers): let git see it unchanged
        sys.stdout.buffer.write(text.encode("utf-8"))
        return
    out = json.dumps(strip(nb), sort_keys=True, indent=1, ensure_ascii=False) + "\n"
    sys.stdout.buffer.write(out.encode("utf-8"))


if __name__ == "__main__":
    main()
