"""The tests run against the installed wheel: the package, its bundled library and its
type marker come from site-packages, and the versions agree with Cargo.toml."""

import re
import sys
from pathlib import Path

import orient


def test_imported_from_the_installed_wheel_not_the_source_tree(root):
    here = Path(orient.__file__).resolve()
    assert "site-packages" in here.parts, here
    assert not here.is_relative_to(root), here
    assert (here.parent / "py.typed").is_file()
    assert (here.parent / "liborient.so").is_file()
    assert Path(sys.prefix).resolve() != Path(sys.base_prefix).resolve(), "not in a virtual environment"


def test_versions_agree(root):
    cargo = re.search(r'^version = "([^"]+)"', (root / "Cargo.toml").read_text(), re.M).group(1)
    assert orient.version() == orient.__version__ == cargo


def test_the_readme_example_runs(root, monkeypatch, capsys):
    text = (root / "README.md").read_text()
    section = text[text.index("## Python"):]
    code = section[section.index("```python\n") + 10:section.index("```\n", section.index("```python\n") + 10)]
    assert len(code.strip().splitlines()) == 5
    monkeypatch.chdir(root)
    exec(compile(code, "README.md", "exec"), {})
    printed = capsys.readouterr().out
    assert printed.count("[") >= 2, printed
