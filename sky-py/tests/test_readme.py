"""The Python blocks of the package's README and of docs/python.md run as written."""

from __future__ import annotations

import pathlib
import re

import pytest

HERE = pathlib.Path(__file__).resolve().parent
PAGES = [HERE.parent / "README.md", HERE.parent.parent / "docs" / "python.md"]


def blocks(page):
    text = page.read_text(encoding="utf-8")
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_python_blocks_run(page, capsys):
    found = blocks(page)
    assert found, f"{page} has no python block"
    for code in found:
        exec(compile(code, str(page), "exec"), {"__name__": "__main__"})
