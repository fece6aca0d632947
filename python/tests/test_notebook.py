"""The example notebook (examples/impact.ipynb) runs end to end in a fresh kernel."""

import pytest

from conftest import ROOT


def test_the_example_notebook_runs():
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("matplotlib")
    path = ROOT / "examples" / "impact.ipynb"
    notebook = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(notebook, timeout=120, kernel_name="python3",
                                     resources={"metadata": {"path": str(path.parent)}})
    client.execute()
    outputs = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    # The report shows itself as HTML: its table and its force–time figure.
    html = [o for o in outputs if o.output_type == "execute_result" and "text/html" in o.get("data", {})]
    assert any("<svg" in o["data"]["text/html"] and "impact-report" in o["data"]["text/html"] for o in html)
    images = [o for o in outputs if "image/png" in o.get("data", {})]
    assert len(images) >= 3
