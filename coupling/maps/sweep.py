"""Solving the points of a map: local worker processes or a Dask cluster, a point store, interruption.

Part of :mod:`lubedyn.maps` (the package docstring gives the overview)."""
from __future__ import annotations

import concurrent.futures as cf
import contextlib
import json
import logging
import os
import time
from pathlib import Path

from lubedyn.lubrication.errors import InputError

from lubedyn import outputs
from lubedyn.outputs import die_with_parent as _die_with_parent
from lubedyn.maps.filmmap import _json_default
from lubedyn.maps.provenance import code_fingerprint, point_hash

log = logging.getLogger(__name__)

# ---------------------------------------------------------------------------
# solving points


def _solve_point(evaluate, params, point):
    """Worker: ("ok", outputs) or ("failed", message); never raises (one failure must not stop a pool)."""
    try:
        result = evaluate(params, point)
        return "ok", {k: float(v) for k, v in result.items()}
    except Exception as exc:  # noqa: BLE001 - recorded and reported by the caller
        return "failed", f"{type(exc).__name__}: {' '.join(str(exc).split())}"


def _solve_chunk(evaluate, params, points, store_root=None, keys=None):
    """Worker: :func:`_solve_point` for each point of a chunk, in order, in one process (a kind may
    cache work shared by the chunk, e.g. an EHL solve shared by every slide-to-roll ratio).  With
    ``store_root`` (a local folder), each solved point is stored at once (``keys``: the point hashes),
    so that an interrupted or killed build keeps every point finished before it stopped."""
    store = _PointStore(store_root) if store_root is not None else None
    out = []
    for i, p in enumerate(points):
        status, payload = _solve_point(evaluate, params, p)
        if store is not None and status == "ok":
            store.put(keys[i], p, payload)
        out.append((status, payload))
    return out


def _chunks(points, todo) -> list:
    """``todo`` indices grouped by every coordinate but the last (one line of the last axis per chunk)."""
    groups: dict = {}
    for i in todo:
        key = tuple(points[i].values())[:-1]
        groups.setdefault(key, []).append(i)
    return list(groups.values())


def _limit_threads():
    """One BLAS thread per worker process (the workers already fill the cores)."""
    try:
        from threadpoolctl import threadpool_limits

        threadpool_limits(1)
    except Exception:  # noqa: BLE001 - threadpoolctl is optional
        pass


def init_worker(parent_pid: int):
    """Pool initializer: ignore SIGINT (the parent handles Ctrl-C and stops the workers), die with the
    parent, one BLAS thread, no background compilation of kernels."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})  # blocked by the parent while forking
    _die_with_parent(parent_pid)
    _limit_threads()
    # the workers are the parallelism: no second process compiling kernels beside each (lubedyn.dynamics.specialise)
    os.environ["LUBEDYN_BACKGROUND_COMPILE"] = "0"
    os.environ["LUBEDYN_OUTPUT_WORKERS"] = "0"  # nor forked writers of frames and figures (lubedyn.outputs)


@contextlib.contextmanager
def sigint_blocked():
    """Block SIGINT in this thread while workers are forked (they inherit the mask and set SIG_IGN
    before unblocking), so that a Ctrl-C at that moment reaches the parent only."""
    import signal
    import threading

    can = hasattr(signal, "pthread_sigmask") and threading.current_thread() is threading.main_thread()
    if can:
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        if can:
            signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


def stop_pool(pool, timeout: float = 3.0):
    """Cancel every pending chunk and end the workers now (an interrupt or an error): the points
    they finished are already stored."""
    processes = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for proc in processes:
        with contextlib.suppress(Exception):
            proc.terminate()
    deadline = time.monotonic() + timeout
    for proc in processes:
        with contextlib.suppress(Exception):
            proc.join(max(0.0, deadline - time.monotonic()))
            if proc.is_alive():
                proc.kill()
                proc.join(1.0)


def default_workers() -> int:
    """Cores this process may use (``os.sched_getaffinity``)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover
        return max(1, os.cpu_count() or 1)


class _PointStore:
    """One small JSON file per solved point, keyed by the point hash, written atomically."""

    def __init__(self, root):
        self.root = Path(root) if root is not None else None
        self.memory: dict = {}

    def get(self, key):
        if key in self.memory:
            return self.memory[key]
        if self.root is None:
            return None
        path = self.root / f"{key}.json"
        if path.is_file():
            try:
                return json.loads(path.read_text())["outputs"]
            except (ValueError, KeyError, OSError):
                log.warning("ignoring unreadable cached point %s", path)
        return None

    def put(self, key, point, result, *, write=True):
        self.memory[key] = result
        if self.root is not None and write:
            outputs.write_text(self.root / f"{key}.json",
                               json.dumps({"point": point, "outputs": result}, default=_json_default))


def solve_points(kind, params: dict, points: list, *, workers=None, scheduler=None, store=None, progress=True,
                 code=None, desc="points") -> tuple[list, dict]:
    """Solve ``points`` (list of {axis name: value}); returns (results, info).

    ``results[i]`` is the output dict or None (failed: ``info["failed"]``
    lists (index, point, message)).  Cached points come from ``store``; new
    ones are stored as soon as they arrive.
    """
    store = store if store is not None else _PointStore(None)
    code = code if code is not None else code_fingerprint(kind)
    keys = [point_hash(kind.name, params, p, code) for p in points]
    results: list = [store.get(k) for k in keys]
    todo = [i for i, r in enumerate(results) if r is None]
    info = {"cached": len(points) - len(todo), "solved": 0, "failed": [], "backend": "none needed"}
    if not todo:
        return results, info
    from tqdm.auto import tqdm

    bar = tqdm(total=len(todo), desc=desc, unit="pt", disable=None if progress else True, leave=False)

    def accept(i, status, payload, stored=False):
        if status == "ok":
            results[i] = payload
            store.put(keys[i], points[i], payload, write=not stored)
            info["solved"] += 1
        else:
            info["failed"].append((i, points[i], payload))
            log.warning("map point %s failed: %s", points[i], payload)
        bar.update(1)

    workers = workers or min(default_workers(), len(todo))
    try:
        if scheduler is not None:
            info["backend"] = _solve_dask(kind, params, points, todo, scheduler, accept)
        elif workers <= 1 or len(todo) == 1:
            info["backend"] = "serial (this process)"
            for i in todo:
                accept(i, *_solve_point(kind.evaluate, params, points[i]))
        else:
            import multiprocessing

            info["backend"] = f"local processes ({workers})"
            ctx = multiprocessing.get_context("fork") if hasattr(os, "fork") else None
            pool = cf.ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=init_worker,
                                          initargs=(os.getpid(),))
            root = str(store.root) if store.root is not None else None
            try:
                with sigint_blocked():
                    futures = {pool.submit(_solve_chunk, kind.evaluate, params, [points[i] for i in chunk],
                                           root, [keys[i] for i in chunk]): chunk
                               for chunk in _chunks(points, todo)}
                for fut in cf.as_completed(futures):
                    for i, r in zip(futures[fut], fut.result()):
                        accept(i, *r, stored=root is not None)
            except BaseException:  # Ctrl-C or an error: do not wait for the queued points
                stop_pool(pool)
                raise
            pool.shutdown(wait=True)
    finally:
        bar.close()
    return results, info


def run_on_dask(scheduler, key: str, calls: list, accept, error=InputError) -> str:
    """Submit ``calls`` (tuples ``(function, *args)``) to a Dask distributed cluster and hand each result
    to ``accept(k, result)`` as it finishes (k: the call's index); returns the backend's description.

    ``scheduler``: an address, a Client or a cluster (``key``: the setting that named it, for messages;
    ``error``: the one-line error class).  A client this function opens is closed at the end; an
    interrupt or an error cancels the calls the cluster has not done yet.  Used by map sweeps and by
    studies (:mod:`lubedyn.scenes.study`)."""
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise error(f"{key} needs dask.distributed (pip install lubedyn[dask])") from None
    own = not isinstance(scheduler, Client)
    if own:
        address = getattr(scheduler, "scheduler_address", scheduler)
        try:
            client = Client(address, timeout="10s")
        except (OSError, TimeoutError, ValueError) as exc:
            raise error(f"{key} = {address!r}: cannot connect ({' '.join(str(exc).split())})") from None
    else:
        client = scheduler
    try:
        futures = [client.submit(fn, *args, pure=False) for fn, *args in calls]
        index = {f.key: k for k, f in enumerate(futures)}
        try:
            for fut in as_completed(futures):
                accept(index[fut.key], fut.result())
        except BaseException:  # Ctrl-C or an error: cancel what the cluster has not done yet
            with contextlib.suppress(Exception):
                client.cancel(futures)
            raise
        return f"dask ({client.scheduler.address})"
    finally:
        if own:
            client.close()


def _solve_dask(kind, params, points, todo, scheduler, accept) -> str:
    """Solve on a Dask distributed cluster, one line of the last axis per task (:func:`_chunks`)."""
    chunks = _chunks(points, todo)

    def take(k, results):
        for i, r in zip(chunks[k], results):
            accept(i, *r)

    return run_on_dask(scheduler, "build.scheduler",
                       [(_solve_chunk, kind.evaluate, params, [points[i] for i in chunk]) for chunk in chunks], take)
