"""docs/protocol.md's command table is the one the daemon is built from (proto/commands.def)."""
import subprocess

from conftest import BUILD, ROOT


def test_protocol_document_lists_exactly_the_daemons_commands():
    table = subprocess.run([str(BUILD / "bin" / "postured"), "--protocol-table"],
                           capture_output=True, text=True, check=True).stdout
    doc = (ROOT / "docs" / "protocol.md").read_text()
    assert table.strip(), "the daemon printed no table"
    assert table in doc, \
        "docs/protocol.md is out of date: paste `postured --protocol-table` into it"
    # every command of the table appears once in the document
    rows = [line for line in table.splitlines() if line.startswith("| `")]
    assert len(rows) >= 25
    for row in rows:
        assert doc.count(row) == 1
