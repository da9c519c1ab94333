"""The citations: works named by authors and title, DOIs well formed, docs/references.md up to date.

``docs/references.md`` lists every work the code implements or follows with the
modules that use it; the docstrings cite the same works in numpydoc ``References``
sections. These tests read the files as text: nothing is imported.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "medialaxis"
REFERENCES = ROOT / "docs" / "references.md"

#: "paper 000" and the like: the shared papers' file numbers, which mean nothing to a reader.
PAPER_NUMBER = re.compile(r"paper\s*0\d\d", re.IGNORECASE)
#: A DOI as written after "doi:" or in a doi.org address.
DOI_MENTION = re.compile(r"(?:\bdoi:\s*|doi\.org/)(\S+)", re.IGNORECASE)
#: The DOI syntax (the "10." directory indicator, a registrant code of digits, a suffix).
DOI_FORM = re.compile(r"10\.\d{4,9}(?:\.\d+)*/\S+")
#: A module path in the references' "Used in" lists.
MODULE_PATH = re.compile(r"`((?:[a-z_][a-z0-9_]*/)*[a-z_][a-z0-9_]*\.py)`")


def sources() -> list[Path]:
    return sorted(PACKAGE.rglob("*.py"))


def dois_in(text: str) -> list[str]:
    """The DOIs written in ``text``, without the punctuation of the sentence around them."""
    found = []
    for token in DOI_MENTION.findall(text):
        token = token.strip("`<>*")
        while True:
            before = token
            token = token.rstrip(".,;:")
            if token.endswith(")") and token.count(")") > token.count("("):
                token = token[:-1]
            if token == before:
                break
        found.append(token)
    return found


def test_doi_reader_sees_a_bad_doi_and_keeps_parentheses():
    text = "(Sloan, doi:10.1016/0045-7949(93)90239-A), then doi:1145/2461912.2461916. and https://doi.org/10.1109/34.993558."
    assert dois_in(text) == ["10.1016/0045-7949(93)90239-A", "1145/2461912.2461916", "10.1109/34.993558"]
    assert [bool(DOI_FORM.fullmatch(d)) for d in dois_in(text)] == [True, False, True]


def test_no_paper_numbers_in_the_package():
    """Works are cited by authors, title, venue and year, never as "paper 000".

    Until the docstring patches of the files other sessions were editing
    (issue 33.5 report) are applied, this lists them.
    """
    hits = [
        f"{path.relative_to(ROOT)}:{number}: {line.strip()}"
        for path in sources()
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
        if PAPER_NUMBER.search(line)
    ]
    assert not hits, "cite the work, not the shared file number:\n" + "\n".join(hits)


def test_every_doi_has_the_doi_form():
    written = {str(path.relative_to(ROOT)): dois_in(path.read_text(encoding="utf-8")) for path in sources()}
    written["docs/references.md"] = dois_in(REFERENCES.read_text(encoding="utf-8"))
    bad = [f"{where}: {doi}" for where, dois in written.items() for doi in dois if not DOI_FORM.fullmatch(doi)]
    assert not bad, "not of the form 10.NNNN/...:\n" + "\n".join(bad)
    # the references name a DOI for most works, and the code cites several
    assert len(written["docs/references.md"]) >= 30
    assert sum(len(dois) for where, dois in written.items() if where.startswith("src")) >= 10


def test_modules_named_in_the_references_exist():
    text = REFERENCES.read_text(encoding="utf-8")
    entries = text[text.index("\n## ") :]  # the introduction above names the tests, not modules
    named = sorted(set(MODULE_PATH.findall(entries)))
    assert len(named) >= 40
    missing = [name for name in named if not (PACKAGE / name).is_file()]
    assert not missing, "docs/references.md names modules that are not in src/medialaxis: " + ", ".join(missing)
