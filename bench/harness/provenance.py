"""What a figure came from: the commit of the code, the dermis binary's version, the CPU."""
import subprocess

from bench.harness.paths import ROOT


def git_commit():
    """The repository's HEAD, short ("" outside a git checkout)."""
    return subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                          text=True).stdout.strip()


def dermis_version(binary):
    """What `binary --version` prints, e.g. "dermis 0.1.0"."""
    return subprocess.run([binary, "--version"], capture_output=True, text=True).stdout.strip()


def cpu_model():
    """The CPU's model name from /proc/cpuinfo ("" where there is none)."""
    try:
        with open("/proc/cpuinfo") as f:
            return next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        return ""
