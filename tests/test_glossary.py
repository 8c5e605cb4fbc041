"""docs/glossary.md points each term to the notebook that first teaches it.

Every entry ends with a pointer: ``(NN)`` or ``(NN, MM, ...)`` (notebook numbers), or
``(`maths.md`, *Section*)`` for a term no notebook teaches. The first number must be the notebook
that *first teaches* the term: one of the entry's names appears in that notebook's markdown and in
no earlier notebook's markdown. Later numbers must be later notebooks whose markdown uses the term.

An entry's names are the parts of its bold head (split at commas, without code spans and
parentheses), unless :data:`NAMES` lists them: what the notebooks actually write. Two kinds of
earlier text do not count as teaching: the course map of notebook 00 (a table naming every topic
of the series) and the few forward or passing mentions listed, each with its reason, in
:data:`EARLIER_MENTIONS`.
"""

from __future__ import annotations

import re
from pathlib import Path

import nbformat
import pytest

REPO = Path(__file__).resolve().parents[1]
GLOSSARY = REPO / "docs" / "glossary.md"
MATHS = REPO / "docs" / "maths.md"
NOTEBOOKS = REPO / "notebooks"

#: The names searched for, where the bold head is not what the notebooks write.
NAMES: dict[str, list[str]] = {
    "Classical scaling (classical MDS)": ["classical scaling", "classical MDS"],
    "Conformal change of metric": ["conformal"],
    "Courant–Fischer (min–max) principle": ["Courant–Fischer", "min–max"],
    "Eckart–Young theorem": ["Eckart–Young"],
    "Farthest-point sampling": ["farthest-point"],
    "HKS (heat kernel signature)": ["HKS", "heat kernel signature"],
    "Intrinsic Delaunay triangulation, tufted Laplacian": ["intrinsic Delaunay", "tufted"],
    "Irreducible representation (symmetry type)": ["irreducible representation", "symmetry type"],
    "Ky Fan's theorem": ["Ky Fan"],
    "Legendre polynomials": ["Legendre"],
    "Lipschitz function": ["Lipschitz"],
    "Matrix pencil": ["pencil", "generalised eigenproblem", "generalized eigenproblem"],
    "Metric `|K|^α g`": [r"|K|^\alpha g", r"\lvert K\rvert^\alpha g"],
    "Moore–Penrose pseudo-inverse `M⁺`": ["pseudo-inverse", "pinv"],
    "Neumann boundary condition": ["Neumann"],
    "Non-manifold mesh": ["non-manifold"],
    "P1 (piecewise-linear) finite elements": ["P1"],
    "Principal angles": ["principal angle"],
    "Rayleigh–Ritz method": ["Rayleigh–Ritz"],
    "Regularised PCA": ["regularised PCA", "regularized PCA"],
    "Shift-invert Lanczos": ["shift-invert"],
    "Umbrella Laplacian": ["umbrella"],
    "Witness function": ["witness"],
    "WKS (wave kernel signature)": ["WKS", "wave kernel signature"],
    "Worst-case constant `C(V)`": ["worst-case constant", "C(V)"],
}

#: Mentions before the teaching notebook that do not teach the term: (entry, notebook) -> why.
EARLIER_MENTIONS: dict[tuple[str, str], str] = {
    ("Cotangent weights, stiffness matrix `W`", "01"):
        "in passing: needle triangles would make cotangent weights explode",
    ("Cotangent weights, stiffness matrix `W`", "02"):
        "a forward pointer: 'the next notebook derives both'",
    ("Courant–Fischer (min–max) principle", "05"):
        "forward pointers: the paper's proof through it is walked through in notebook 07",
    ("Courant–Fischer (min–max) principle", "06"):
        "in passing: Ky Fan's principle is called the sum version of Courant–Fischer",
    ("Regularised PCA", "06"): "in passing: eq. (6) is the one regularized PCA builds on",
    ("Non-manifold mesh", "00"): "a forward pointer: 'notebook 04 shows how'",
}

_COURSE_MAP = re.compile(r"^\|\s*#\s*\|\s*notebook\s*\|", re.MULTILINE)
_ENTRY = re.compile(r"^\*\*(?P<head>.+?)\.\*\*\s(?P<body>.*?)(?=\n\s*\n|\Z)", re.MULTILINE | re.DOTALL)
_NOTEBOOK_POINTER = re.compile(r"\((?P<numbers>\d\d(?:, \d\d)*)\)\.?$")
_MATHS_POINTER = re.compile(r"\(`maths\.md`, \*(?P<section>[^*]+)\*\)\.?$")


def normalise(text: str) -> str:
    """Lower case, without the markup that splits words (``$``, ``*``, backticks, thin spaces)."""
    text = text.lower().replace("$", "").replace("*", "").replace("`", "").replace("\\,", " ")
    return re.sub(r"\s+", " ", text)


def mentions(text: str, names: list[str]) -> bool:
    return any(re.search(r"(?<![a-z0-9])" + re.escape(normalise(n).strip()), text) for n in names)


def notebook_markdown() -> dict[str, str]:
    """Notebook number -> its markdown, normalised (without notebook 00's course map)."""
    out = {}
    for path in sorted(NOTEBOOKS.glob("[0-9][0-9]_*.ipynb")):
        cells = nbformat.read(path, as_version=4).cells
        texts = [c.source for c in cells if c.cell_type == "markdown"]
        if path.name.startswith("00"):
            texts = [t for t in texts if not _COURSE_MAP.search(t)]
        out[path.name[:2]] = normalise("\n".join(texts))
    return out


def maths_sections() -> dict[str, str]:
    """docs/maths.md: section heading (without its code span) -> the section's text, normalised."""
    parts = re.split(r"^## ", MATHS.read_text(encoding="utf-8"), flags=re.MULTILINE)[1:]
    return {re.sub(r"\s*\(.*$", "", p.splitlines()[0]).strip(): normalise(p) for p in parts}


def entries(text: str) -> dict[str, str]:
    """Glossary text -> {bold head: entry body}."""
    return {m["head"]: " ".join(m["body"].split()) for m in _ENTRY.finditer(text)}


def names_of(head: str) -> list[str]:
    if head in NAMES:
        return NAMES[head]
    bare = re.sub(r"`[^`]*`", "", head)
    bare = re.sub(r"\([^)]*\)", "", bare)
    return [part.strip() for part in bare.split(",") if part.strip()]


def problems(head: str, body: str, markdown: dict[str, str], sections: dict[str, str]) -> list[str]:
    """What is wrong with one entry's pointer (empty when nothing is)."""
    names = names_of(head)
    found = [k for k, text in markdown.items() if mentions(text, names)]
    maths = _MATHS_POINTER.search(body)
    if maths:
        section = maths["section"]
        if section not in sections:
            return [f"maths.md has no section '## {section}'"]
        out = [] if mentions(sections[section], names) else [f"maths.md, {section}, never says {names}"]
        if found:
            out.append(f"notebooks {found} use {names}: point to the first that teaches it")
        return out
    pointer = _NOTEBOOK_POINTER.search(body)
    if not pointer:
        return ["no pointer at the end of the entry: (NN), (NN, MM) or (`maths.md`, *Section*)"]
    numbers = pointer["numbers"].split(", ")
    out = [f"no notebook {k}" for k in numbers if k not in markdown]
    if out:
        return out
    first = numbers[0]
    if first not in found:
        out.append(f"notebook {first} never mentions {names}")
    earlier = [k for k in found if k < first and (head, k) not in EARLIER_MENTIONS]
    if earlier:
        out.append(f"{names} already appear in notebook(s) {earlier}, before {first}")
    if numbers != sorted(set(numbers)):
        out.append(f"pointers {numbers} are not in increasing order")
    out += [f"later notebook {k} never mentions {names}" for k in numbers[1:] if k not in found]
    return out


@pytest.fixture(scope="module")
def markdown():
    return notebook_markdown()


@pytest.fixture(scope="module")
def sections():
    return maths_sections()


GLOSSARY_ENTRIES = entries(GLOSSARY.read_text(encoding="utf-8"))


def test_the_glossary_has_its_entries():
    assert len(GLOSSARY_ENTRIES) > 50
    unknown = (set(NAMES) | {head for head, _ in EARLIER_MENTIONS}) - set(GLOSSARY_ENTRIES)
    assert not unknown, f"NAMES or EARLIER_MENTIONS name entries the glossary lacks: {unknown}"


@pytest.mark.parametrize("head", sorted(GLOSSARY_ENTRIES))
def test_entry_points_to_the_notebook_that_first_teaches_it(head, markdown, sections):
    assert not problems(head, GLOSSARY_ENTRIES[head], markdown, sections), (
        f"glossary entry '{head}': {problems(head, GLOSSARY_ENTRIES[head], markdown, sections)}")


def test_each_earlier_mention_exists_and_is_earlier(markdown):
    for (head, notebook), reason in EARLIER_MENTIONS.items():
        first = _NOTEBOOK_POINTER.search(GLOSSARY_ENTRIES[head])["numbers"].split(", ")[0]
        assert notebook < first, f"'{head}': {notebook} is not before {first} ({reason})"
        assert mentions(markdown[notebook], names_of(head)), (
            f"'{head}': notebook {notebook} no longer mentions it; drop the exception ({reason})")


OLD_NUMBERING = """
**Canonical form.** An embedding of a surface in Euclidean space whose Euclidean distances
approximate the surface's geodesic distances (07).

**Functional map.** A linear map `C` between function spaces of two shapes (09).

**HKS (heat kernel signature).** `h_t(x) = Σᵢ e^{−λᵢ t} φᵢ(x)²` (09).

**Schur complement.** For a block matrix `[[P, Q], [Qᵀ, R]]`, the matrix `R − Qᵀ P⁻¹ Q` (04, 05).

**Witness function.** For an `n`-dimensional subspace `V`, a nonzero `f` (04).
"""


def test_the_old_numbering_fails(markdown, sections):
    old = entries(OLD_NUMBERING)
    assert len(old) == 5
    for head, body in old.items():
        assert problems(head, body, markdown, sections), f"the old pointer of '{head}' passed"


def test_an_edition_carries_the_glossary_beside_its_notebooks(tmp_path):
    """The student edition and the nbgrader assignments are served or handed out alone, where
    ``../docs/`` does not exist (issue 43: the link did nothing in JupyterLab): each copy of a
    notebook links ``glossary.md`` beside it, and the glossary and every page it links are there."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("student_edition", REPO / "scripts" / "student_edition.py")
    edition = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(edition)
    for nb in edition.series(NOTEBOOKS):
        edition.copy_for_edition(nb, tmp_path / nb.name)
        copy = nbformat.read(tmp_path / nb.name, as_version=4)
        header = copy.cells[0].source
        assert "](glossary.md)" in header and "../docs/" not in header, nb.name
        assert [c.source for c in copy.cells[1:]] == [c.source for c in nbformat.read(nb, as_version=4).cells[1:]]
    assert (tmp_path / "glossary.md").read_text(encoding="utf-8") == GLOSSARY.read_text(encoding="utf-8")
    for target in re.findall(r"\]\(([^)#\s]+)\)", GLOSSARY.read_text(encoding="utf-8")):
        if not re.match(r"[a-z]+:", target):
            assert (tmp_path / target).is_file(), f"the glossary links {target}, which the edition lacks"
