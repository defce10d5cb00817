"""The Python examples of the documentation run as pasted: the README's snippet and the
two-body example of docs/python.md, each executed as written (in a temporary folder, since
the README's writes a result set), with what they state checked."""

import re

import numpy as np

from conftest import REPO


def _blocks(path, after):
    text = (REPO / path).read_text(encoding="utf-8")
    text = text[text.index(after):]
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


def test_readme_python_snippet_runs_as_pasted(tmp_path, monkeypatch):
    code = _blocks("README.md", "## Python")[0]
    monkeypatch.chdir(tmp_path)
    scope = {}
    exec(compile(code, "README.md", "exec"), scope)
    r = scope["r"]
    assert r.converged, r.message
    assert (tmp_path / "out" / "py-paper" / "summary.json").is_file()
    assert scope["m"].cells.shape == (2, 3)


def test_two_body_example_of_the_python_docs(tmp_path, monkeypatch):
    code = _blocks("docs/python.md", "### Two bodies")[0]
    monkeypatch.chdir(tmp_path)
    scope = {}
    exec(compile(code, "docs/python.md", "exec"), scope)
    r = scope["r"]
    assert r.converged, r.message
    # E δ / (2 H): two unit squares in series, ν = 0.
    assert np.allclose(r.contact["pressure"], 5.0, rtol=1e-10, atol=0)
