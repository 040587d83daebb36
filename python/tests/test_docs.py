"""Every Python example of README.md and docs/guide/python.md runs (from
the repository's root, as a reader would run it), and the docstring
examples of the package pass as doctests."""

import doctest
import re

import pytest

import sticky
import sticky.errors

from conftest import ROOT

PAGES = ["README.md", "docs/guide/python.md"]

# A fenced Python block: ```python … ```.
BLOCK = re.compile(r"^```python\n(.*?)^```", re.MULTILINE | re.DOTALL)


def examples():
    for page in PAGES:
        text = (ROOT / page).read_text(encoding="utf-8")
        for k, m in enumerate(BLOCK.finditer(text)):
            line = text.count("\n", 0, m.start()) + 2
            yield pytest.param(page, line, m.group(1), id=f"{page}:{line}")


def test_the_pages_have_examples():
    assert len(list(examples())) >= 3


@pytest.mark.parametrize("page, line, code", list(examples()))
def test_example_runs(page, line, code, monkeypatch):
    monkeypatch.chdir(ROOT)
    # Line numbers of a failure point into the page.
    source = "\n" * (line - 1) + code
    exec(compile(source, str(ROOT / page), "exec"), {"__name__": "__example__"})


@pytest.mark.parametrize("module", [sticky, sticky.errors], ids=lambda m: m.__name__)
def test_docstrings(module):
    failed, tried = doctest.testmod(module, extraglobs={"sticky": sticky})
    assert tried > 0 and failed == 0
