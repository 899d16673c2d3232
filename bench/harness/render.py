"""Running `dermis render`: its command line, the process's times, and what it prints."""
import re
import resource
import subprocess
import time
from dataclasses import dataclass
from typing import Optional

# `dermis render` ends with "dermis: wrote OUT in 1.302 s (2.1 Mrays/s, 64 samples)": the
# render stage's wall time (in milliseconds since 2026-12-03, in 0.1 s steps before),
WROTE_RE = re.compile(r"in ([0-9.]+) s \(([0-9.]+) Mrays/s, ([0-9]+) samples\)")
# and says "time limit reached: 12..14 samples per pixel" when --time-limit stopped it.
LIMIT_RE = re.compile(r"time limit reached: ([0-9]+)\.\.([0-9]+) samples per pixel")


def command(binary, scene, out, spp=None, res=None, seed=None, threads=None, quiet=True, no_png=True, extra=()):
    """The `dermis render` command line writing `out`; options left None are the scene's.
    res: "WIDTHxHEIGHT"; extra: further arguments (--time-limit 2, --sampler sobol, ...)."""
    cmd = [binary, "render", scene]
    for flag, value in (("--spp", spp), ("--res", res), ("--seed", seed), ("--threads", threads)):
        if value is not None:
            cmd += [flag, str(value)]
    if quiet:
        cmd.append("-q")
    if no_png:
        cmd.append("--no-png")
    return cmd + ["-o", out] + list(extra)


@dataclass
class Finished:
    """A finished process: its command, exit status, what it printed, its times."""
    cmd: list
    returncode: int
    log: str  # its stderr (with merge_output, stdout and stderr as they came)
    wall: float  # seconds from start to exit
    cpu: Optional[float] = None  # user + system seconds (the kernel's: little moved by other load)


class DermisError(RuntimeError):
    """A process that failed, with what it printed."""

    def __init__(self, finished):
        self.finished = finished
        super().__init__(f"{' '.join(map(str, finished.cmd))} failed (exit {finished.returncode}):\n{finished.log}")


def run(cmd, cwd=None, timeout=None, check=True, merge_output=False):
    """Runs cmd to its end, its output captured; DermisError if it fails and `check`."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run(cmd, cwd=cwd, timeout=timeout, text=True, errors="replace", stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT if merge_output else subprocess.PIPE)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    done = Finished(list(cmd), p.returncode, p.stdout if merge_output else p.stderr, wall, cpu)
    if check and p.returncode != 0:
        raise DermisError(done)
    return done


def render(binary, scene, out, cwd=None, timeout=None, check=True, **options):
    """`dermis render` of scene into out (options: those of command()); its Finished."""
    return run(command(binary, scene, out, **options), cwd=cwd, timeout=timeout, check=check)


@dataclass
class RenderStats:
    """What `dermis render` reports when its render stage ends."""
    seconds: float  # the render stage's wall time
    printed: str  # that time as printed (its decimals: the build's resolution)
    mrays: float  # millions of rays per second
    samples: int  # camera samples, all pixels together


def render_stats(log):
    """The RenderStats in a `dermis render` log, None if it has none."""
    m = WROTE_RE.search(log)
    return RenderStats(float(m.group(1)), m.group(1), float(m.group(2)), int(m.group(3))) if m else None


def time_limit_range(log):
    """(fewest, most) samples per pixel when --time-limit stopped the render, else None."""
    m = LIMIT_RE.search(log)
    return (int(m.group(1)), int(m.group(2))) if m else None
