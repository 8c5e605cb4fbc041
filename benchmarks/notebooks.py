"""Benchmark: wall time and peak memory of every notebook, each run in a fresh kernel.

Each notebook in ``notebooks/`` (or the paths given) is executed top to bottom with nbclient, one at
a time, in a new IPython kernel whose working directory is the notebook's folder (as in JupyterLab
and nbval). While it runs, a thread samples the resident memory (RSS) of the kernel process and all
its children with psutil every 50 ms; the peak of that sum is reported, together with the kernel's
own high-water mark (``VmHWM``), which catches spikes shorter than a sampling interval.

Budgets (the course targets a 2-core machine and Binder's ~2 GB): each notebook under 60 s and
under 1.2 GB, the whole series under 5 minutes. The wall time includes starting the kernel,
because a reader pays for it too. Wall times depend on the machine's load, so the load average is
printed with the table, and the CPU time of the kernel tree (user + system), which depends much
less on load, is printed beside it. Run:

    python benchmarks/notebooks.py              # table; exit code 1 only if a notebook fails
    python benchmarks/notebooks.py --strict     # also exit 1 when anything is over budget
    python benchmarks/notebooks.py notebooks/03_laplace_beltrami.ipynb --json build/nb.json
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import threading
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import nbformat
import psutil
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError, CellTimeoutError, DeadKernelError

REPO = Path(__file__).resolve().parent.parent
NOTEBOOKS = REPO / "notebooks"
MB = 1e6  # budgets are in decimal units: 1.2 GB = 1200 MB


@dataclass
class Result:
    notebook: str
    seconds: float
    peak_mb: float
    cpu_seconds: float
    cells: int
    error: str | None = None


class TreeMemorySampler(threading.Thread):
    """Samples the summed RSS of a process and its descendants until stopped; keeps the peak."""

    def __init__(self, pid: int, interval: float = 0.05) -> None:
        super().__init__(daemon=True)
        self.pid, self.interval = pid, interval
        self.peak = 0
        self.cpu_seconds = 0.0
        self._stop_event = threading.Event()

    def _tree(self) -> list:
        """The kernel process and its children (empty once the kernel has exited)."""
        try:
            root = psutil.Process(self.pid)
            return [root, *root.children(recursive=True)]
        except psutil.NoSuchProcess:
            return []

    def sample(self) -> int:
        total = 0
        for p in self._tree():
            try:
                total += p.memory_info().rss
            except (psutil.NoSuchProcess, psutil.AccessDenied):
                pass
        return total

    def high_water_mark(self) -> int:
        """The kernel process's own peak RSS (Linux ``VmHWM``), 0 where unavailable."""
        try:
            with open(f"/proc/{self.pid}/status") as fh:
                for line in fh:
                    if line.startswith("VmHWM:"):
                        return int(line.split()[1]) * 1024
        except OSError:
            pass
        return 0

    def run(self) -> None:
        while not self._stop_event.is_set():
            self.peak = max(self.peak, self.sample())
            self._stop_event.wait(self.interval)

    def cpu_time(self) -> float:
        """User + system CPU seconds of the kernel process tree so far (less load-dependent than wall time)."""
        total = 0.0
        for p in self._tree():
            try:
                t = p.cpu_times()
                total += t.user + t.system + t.children_user + t.children_system
            except (psutil.NoSuchProcess, psutil.AccessDenied):
                pass
        return total

    def stop(self) -> int:
        """Stop sampling and return the peak in bytes (sampled tree sum or kernel high-water mark)."""
        self.peak = max(self.peak, self.sample(), self.high_water_mark())
        self.cpu_seconds = self.cpu_time()
        self._stop_event.set()
        self.join()
        return self.peak


def kernel_pid(client: NotebookClient) -> int:
    """PID of the kernel process nbclient started (local provisioner)."""
    km = client.km
    provisioner = getattr(km, "provisioner", None)
    process = getattr(provisioner, "process", None)
    if process is not None:
        return int(process.pid)
    raise RuntimeError("could not find the kernel process (is the kernel local?)")


def run_notebook(path: Path, timeout: int) -> Result:
    """Execute ``path`` in a fresh kernel (cwd = its folder); return time, peak memory, error."""
    import tempfile

    from jupyter_client.manager import KernelManager

    nb = nbformat.read(path, as_version=4)
    n_cells = sum(c.cell_type == "code" for c in nb.cells)
    # The kernel listens on IPC (unix) sockets, as the site's builder: a TCP kernel warns that its
    # traffic is unencrypted, noise in the table.
    sockets = tempfile.TemporaryDirectory(prefix="lbo-kernel-")
    km = KernelManager(kernel_name="python3", transport="ipc", ip=str(Path(sockets.name) / "kernel"))
    client = NotebookClient(nb, km=km, timeout=timeout, kernel_name="python3",
                            resources={"metadata": {"path": str(path.parent)}})
    error: str | None = None
    start = time.perf_counter()
    sampler: TreeMemorySampler | None = None
    try:
        with client.setup_kernel():
            sampler = TreeMemorySampler(kernel_pid(client))
            sampler.start()
            try:
                for index, cell in enumerate(nb.cells):
                    client.execute_cell(cell, index)
            finally:
                peak = sampler.stop()
    except CellExecutionError as exc:
        error = f"{exc.ename}: {exc.evalue}"[:200]
    except (CellTimeoutError, DeadKernelError) as exc:
        error = f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}"[:200]
    finally:
        seconds = time.perf_counter() - start
        if km.has_kernel:  # nbclient shuts down only kernel managers it created itself
            km.shutdown_kernel(now=True)
        sockets.cleanup()
    return Result(path.name, seconds, (peak if sampler else 0) / MB,
                  sampler.cpu_seconds if sampler else 0.0, n_cells, error)


def load_average() -> str:
    try:
        return "load average {:.1f} {:.1f} {:.1f} on {} cores".format(*os.getloadavg(), os.cpu_count())
    except OSError:
        return f"{os.cpu_count()} cores"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebooks", nargs="*", type=Path, help="notebooks to run (default: notebooks/*.ipynb)")
    parser.add_argument("--strict", action="store_true", help="exit with code 1 when a budget is exceeded")
    parser.add_argument("--max-seconds", type=float, default=60.0, help="budget per notebook (default 60)")
    parser.add_argument("--max-mb", type=float, default=1200.0, help="memory budget per notebook in MB (default 1200)")
    parser.add_argument("--max-total-seconds", type=float, default=300.0, help="budget for the series (default 300)")
    parser.add_argument("--timeout", type=int, default=600, help="per-cell timeout in seconds (default 600)")
    parser.add_argument("--json", type=Path, help="also write the results to this JSON file")
    args = parser.parse_args(argv)

    paths = [p.resolve() for p in args.notebooks] or sorted(NOTEBOOKS.glob("*.ipynb"))
    if not paths:
        print(f"no notebooks found in {NOTEBOOKS}", file=sys.stderr)
        return 1
    print(f"{len(paths)} notebooks, {load_average()} (before)")
    print(f"{'notebook':<34}{'cells':>6}{'wall s':>9}{'cpu s':>8}{'peak MB':>9}  status")
    results: list[Result] = []
    over: list[str] = []
    for path in paths:
        r = run_notebook(path, args.timeout)
        results.append(r)
        flags = []
        if r.error:
            flags.append(f"ERROR {r.error}")
        if r.seconds > args.max_seconds:
            flags.append(f"over {args.max_seconds:.0f} s")
        if r.peak_mb > args.max_mb:
            flags.append(f"over {args.max_mb:.0f} MB")
        if not r.error and flags:
            over.append(r.notebook)
        print(f"{r.notebook:<34}{r.cells:>6}{r.seconds:>9.1f}{r.cpu_seconds:>8.1f}{r.peak_mb:>9.0f}  {'; '.join(flags) or 'ok'}", flush=True)
    total = sum(r.seconds for r in results)
    total_flag = f"over {args.max_total_seconds:.0f} s" if total > args.max_total_seconds else "ok"
    if total > args.max_total_seconds:
        over.append("total")
    print(f"{'total':<34}{sum(r.cells for r in results):>6}{total:>9.1f}{sum(r.cpu_seconds for r in results):>8.1f}{max(r.peak_mb for r in results):>9.0f}  {total_flag}")
    print(f"{load_average()} (after). Budgets: < {args.max_seconds:.0f} s and < {args.max_mb:.0f} MB each "
          f"(wall time includes kernel start; cpu = user+system time of the kernel tree, less sensitive to load; peak = RSS of the kernel tree), < {args.max_total_seconds:.0f} s in total.")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps({"load": load_average(), "total_seconds": total,
                                         "notebooks": [asdict(r) for r in results]}, indent=2))
    failed = [r.notebook for r in results if r.error]
    if failed:
        print(f"FAILED: {', '.join(failed)}", file=sys.stderr)
        return 1
    if over:
        print(f"over budget: {', '.join(over)}", file=sys.stderr)
        return 1 if args.strict else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
