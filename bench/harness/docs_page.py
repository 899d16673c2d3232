"""Writing a docs page that a script generates above a marker line, below which people write
their findings by hand: the script rewrites the part above and keeps the part below."""
import os


def findings(path, marker):
    """What the page at path has below its marker, without the blank lines after the marker."""
    if not os.path.exists(path):
        return ""
    with open(path) as f:
        text = f.read()
    return text.split(marker, 1)[1].lstrip("\n") if marker in text else ""


def write_page(path, generated, marker):
    """Writes `generated` (ending with a newline), a blank line, the marker line and the
    findings the page had below it, a blank line apart."""
    kept = findings(path, marker)
    with open(path, "w") as f:
        f.write(generated + "\n" + marker + "\n" + ("\n" + kept if kept else ""))
