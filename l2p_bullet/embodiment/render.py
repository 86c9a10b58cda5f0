"""Rendering off the simulation's critical path: the episode records states, workers draw them.

A frame at 640x480 costs as much as hundreds of physics steps, and the physics is one thread. So while
the arm runs, the :class:`~.record.Recorder` only notes the *state* at each frame time (every joint of
the arm, every block's pose: microseconds), and a :class:`Film` hands those states, a few at a time, to a
small pool of worker processes. Each worker owns a world of its own (its own DIRECT client and EGL
context), teleports it to a state and renders it; it writes the frame's PNG too. The pool starts when
the episode starts, so its workers load while the arm simulates.

Every image depends on its state only (the world is set whole before each frame), so the frames are
the same whichever worker draws them and in whatever order: with ``workers`` 0 the same states are
drawn in this process with the same code, and tests/embodiment/test_render_pool.py checks the two are identical.

Where the EGL plugin cannot start, frames are drawn with TinyRenderer and a one-line note says so; the
renderer used goes into summary.json. A pool never nests: inside a worker process (``evaluate``'s pool,
Ray) rendering runs in that process.
"""

from __future__ import annotations

import multiprocessing
import os
import struct
import sys
import time
import zlib
from concurrent.futures import Future, ProcessPoolExecutor
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..arms import PANDA, ArmSpec
from ..core.lifeline import exit_with_parent
from ..core.scene import Scene
from ..errors import ExecutionError
from .sim.camera import RenderSettings

CHUNK = 8  # states per task: enough to amortise a task's overhead, few enough to keep both cores busy
MAX_WORKERS = 4
SMALL = 320 * 240  # frames with fewer pixels are drawn in-process: starting a worker costs more than they do
WARM_UP = 3  # frames an EGL painter draws and drops: its first two show a few pixels of an older state
SHADOW_RGBA = (0.45, 0.39, 0.30, 1.0)  # the table's wood (table.urdf) in shade
SHADOW_LIFT = 0.0008  # m above the table top: clear of it in the depth buffer, too thin to see as a slab


@dataclass(frozen=True)
class State:
    """What a frame shows: simulated time, the arm's movable joints, each block's base pose (scene order)."""

    t: float
    joints: tuple[float, ...]
    bodies: tuple[tuple[tuple[float, ...], tuple[float, ...]], ...]


def capture(world) -> State:
    """The world's state now (cheap: called during the episode)."""
    from .sim.robot import ARM

    sim = world.sim
    joints = movable_joints(world)
    q = sim.joint_positions(ARM, joints)
    bodies = tuple((tuple(p), tuple(o)) for p, o in (sim.base_pose(n) for n in world.sizes))
    return State(round(world.time, 6), tuple(float(v) for v in q), bodies)


def movable_joints(world) -> list[int]:
    from .sim.robot import ARM

    cached = getattr(world, "_movable_joints", None)
    if cached is None:
        cached = [j.index for j in world.sim.joints(ARM) if j.movable]
        world._movable_joints = cached
    return cached


class Painter:
    """A world of its own that draws states: the scene's blocks, the arm with its visuals, a camera.

    ``renderer`` "egl" falls back to "tiny" where the plugin does not load (``note`` says why)."""

    def __init__(self, scene: Scene, settings: RenderSettings, arm: ArmSpec = PANDA):
        from .sim.camera import Camera
        from .sim.world import World

        self.note = None
        self.renderer = settings.renderer
        try:
            self.world = World(scene, arm=arm, visuals=True, egl=settings.renderer == "egl")
        except ExecutionError as e:
            if settings.renderer != "egl":
                raise
            self.note = f"EGL rendering could not start here ({e}); rendering with TinyRenderer"
            self.renderer = "tiny"
            self.world = World(scene, arm=arm, visuals=True)
        self.camera = Camera(self.world, replace(settings, renderer=self.renderer))
        self.names = list(self.world.sizes)
        self.shadows = drop_shadows(self.world, scene) if self.renderer == "egl" else {}
        if self.renderer == "egl":  # the plugin's first two frames after start differ from later ones (measured)
            for _ in range(WARM_UP):
                self.camera.render()

    def draw(self, state: State) -> np.ndarray:
        from .sim.robot import ARM

        sim = self.world.sim
        sim.reset_joints(ARM, movable_joints(self.world), state.joints)
        for name, (pos, orn) in zip(self.names, state.bodies, strict=True):
            sim.set_base_pose(name, pos, orn)
            if name in self.shadows:
                sim.set_base_pose(self.shadows[name], shadow_at(pos), orn)
        return self.camera.render()

    def close(self) -> None:
        self.world.close()


def drop_shadows(world, scene: Scene) -> dict[str, str]:
    """A flat shadow on the table under each object, for the EGL renderer: its plugin draws no cast shadows
    (the ``shadow`` flag and the light direction reach TinyRenderer only), and without them a block
    carried above the table looks as if it stood on it. Returns object name -> its shadow's body name."""
    out = {}
    for obj in scene.objects:
        name = f"<shadow {obj.name}>"
        if obj.shape == "cube":
            world.sim.add_visual(name, "box", (obj.size / 2, obj.size / 2, 0.0004), SHADOW_RGBA)
        else:
            r = float(np.linalg.norm(obj.footprint(np.zeros(3)), axis=1).max())
            world.sim.add_visual(name, "cylinder", (r, 0.0008), SHADOW_RGBA)
        out[obj.name] = name
    return out


def shadow_at(position) -> tuple[float, float, float]:
    """Where an object centred at ``position`` casts its shadow on the table, the light in LIGHT_DIRECTION."""
    from .sim.camera import LIGHT_DIRECTION

    lx, ly, lz = LIGHT_DIRECTION
    x, y, z = position
    return (x - lx / lz * z, y - ly / lz * z, SHADOW_LIFT)


# --- the worker processes' side ---------------------------------------------------------------------
_PAINTER: Painter | None = None


def _start(scene: Scene, settings: RenderSettings, arm: ArmSpec = PANDA, parent: int | None = None) -> None:
    """Pool initializer: this worker's painter (one world, one EGL context), warmed by one frame; the
    worker ends when ``parent`` (the process that started the pool) dies (``core/lifeline.py``)."""
    import signal

    global _PAINTER
    if parent is not None:
        exit_with_parent(parent)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the main process's: it stops the pool, quietly
    # Mesa's software rasteriser draws in the worker's own thread: no thread of its own per worker (the
    # workers already fill the cores), and no hand-over between threads each frame (about 4 ms of 55)
    os.environ.setdefault("LP_NUM_THREADS", "0")
    _PAINTER = Painter(scene, settings, arm)


def _ready() -> tuple[str, str | None]:
    return _PAINTER.renderer, _PAINTER.note


def _paint(first: int, states: list[State], folder: str | None) -> tuple[str, list[np.ndarray], float]:
    """Draw ``states`` (frames ``first``...), writing ``folder/NNNN.png`` when given; (renderer, images, seconds)."""
    t0 = time.perf_counter()
    images = [_PAINTER.draw(s) for s in states]
    if folder is not None:
        write_pngs(Path(folder), first, images)
    return _PAINTER.renderer, images, time.perf_counter() - t0


def write_pngs(folder: Path, first: int, images: list[np.ndarray]) -> None:
    """``folder/NNNN.png`` from frame ``first`` on (:func:`png_bytes`)."""
    for i, img in enumerate(images, start=first):
        (folder / f"{i:04d}.png").write_bytes(png_bytes(img))


def png_bytes(image: np.ndarray) -> bytes:
    """A lossless PNG of ``image`` (H, W, 3) uint8: no row filter, zlib level 1.

    Rendered frames are mostly flat colour, where zlib alone finds the runs: a third of the time of
    Pillow's level 1 (which also tries a filter on every row) and a smaller file (measured on the default
    video: 2.5 against 8 ms and 61 against 72 KB a 640x480 frame)."""
    img = np.ascontiguousarray(np.asarray(image)[:, :, :3], dtype=np.uint8)
    h, w, _ = img.shape
    rows = np.empty((h, 1 + 3 * w), np.uint8)
    rows[:, 0] = 0  # filter type "none" for every row
    rows[:, 1:] = img.reshape(h, 3 * w)

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)  # 8 bits a channel, RGB, no interlace
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows.tobytes(), 1))
            + chunk(b"IEND", b""))


# --- the episode's side -----------------------------------------------------------------------------
def pool_size(settings: RenderSettings) -> int:
    """Worker processes to use: ``settings.workers``, else the environment's ``L2P_RENDER_WORKERS``, else
    as many as cores (at most 4); none inside a process that is itself a worker (a pool never nests) or
    for frames smaller than 320x240."""
    if settings.workers is not None:
        return max(0, int(settings.workers))
    env = os.environ.get("L2P_RENDER_WORKERS", "").strip()
    if env.isdigit():  # a machine's owner (or a benchmark) may choose; 0 draws in-process
        return min(int(env), 16)
    if multiprocessing.parent_process() is not None or settings.width * settings.height < SMALL:
        return 0
    return min(MAX_WORKERS, os.cpu_count() or 1)


class Film:
    """The frames of one episode: :meth:`add` a state as the episode goes, :meth:`finish` for the images.

    With a pool, states go to the workers ``CHUNK`` at a time while the episode runs; without, they are
    drawn in this process at :meth:`finish`. ``folder``: where the frames' PNGs go (None: nowhere).
    """

    def __init__(self, scene: Scene, settings: RenderSettings, folder: Path | None = None,
                 workers: int | None = None, arm: ArmSpec = PANDA):
        self.scene, self.settings, self.arm = scene, settings.check(), arm
        self.folder = None if folder is None else Path(folder)
        self.states: list[State] = []
        self.paths: list[tuple[str, np.ndarray]] = []  # (mover, planned path) each: the video's top-view inset
        self.workers = pool_size(settings) if workers is None else workers
        self._sent = 0
        self._futures: list[tuple[int, Future]] = []
        self._pool: ProcessPoolExecutor | None = None
        self.render_s = 0.0  # rendering time, summed over the processes that rendered
        self.wall_s = 0.0  # what waiting for the frames cost the episode after its last step
        self.renderer = settings.renderer
        self.note: str | None = None
        if self.folder is not None:
            self.folder.mkdir(parents=True, exist_ok=True)
        if self.workers > 1:
            try:
                self._start_pool(scene)
            except BaseException:  # a Ctrl-C held back while the workers were launched lands here: stop them
                self.close()
                raise

    def _start_pool(self, scene: Scene) -> None:
        """Spawn the workers with Ctrl-C blocked: the children inherit the blocked signal (a Ctrl-C at the
        terminal, sent to them too, never prints a traceback from one still starting up), and a Ctrl-C
        here waits until every child is launched, then stops them (execute_path closes the film).

        Blocking is per thread: a Ctrl-C the kernel hands to another thread of this process (one that started
        earlier, with SIGINT unblocked) still runs Python's handler, and the KeyboardInterrupt surfaced inside
        the executor's start-up, leaving a half-launched child to print a traceback. So the handler is also
        swapped for one that only notes the Ctrl-C, which is raised once the pool has started."""
        import signal
        import threading

        ctx = multiprocessing.get_context("spawn")  # no fork of a process holding a simulator
        blocked = hasattr(signal, "pthread_sigmask")
        old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT}) if blocked else None
        noted: list[int] = []
        main = threading.current_thread() is threading.main_thread()
        handler = signal.signal(signal.SIGINT, lambda signum, frame: noted.append(signum)) if main else None
        try:
            self._pool = ProcessPoolExecutor(self.workers, mp_context=ctx, initializer=_start,
                                             initargs=(scene, self.settings, self.arm, os.getpid()))
            self._warm = [self._pool.submit(_ready) for _ in range(self.workers)]  # launches them all
        finally:
            if main:
                signal.signal(signal.SIGINT, handler)
            if blocked:
                signal.pthread_sigmask(signal.SIG_SETMASK, old)
        if noted:
            raise KeyboardInterrupt

    def add(self, state: State) -> None:
        self.states.append(state)
        if self._pool is not None and len(self.states) - self._sent >= CHUNK:
            self._send()

    def _send(self) -> None:
        batch = self.states[self._sent:]
        if batch:
            folder = None if self.folder is None else str(self.folder)
            self._futures.append((self._sent, self._pool.submit(_paint, self._sent, batch, folder)))
            self._sent = len(self.states)

    def finish(self) -> list[np.ndarray]:
        """Every frame's image, in order (PNGs written when there is a folder); closes the pool."""
        t0 = time.perf_counter()
        try:
            images = self._collect() if self._pool is not None else None
        except BaseException:  # Ctrl-C while waiting for the frames: stop the workers at once
            self.close()
            raise
        self.close(wait=True)
        if images is None:
            images = self._serial()
        self.wall_s = time.perf_counter() - t0
        if self.note:
            print(f"note: {self.note}", file=sys.stderr)
        return images

    def _collect(self) -> list[np.ndarray] | None:
        from concurrent.futures.process import BrokenProcessPool

        self._send()
        images: list[np.ndarray] = []
        used = set()
        try:
            notes = {n for _, n in (f.result() for f in self._warm)}
            for _, fut in self._futures:
                renderer, imgs, seconds = fut.result()
                used.add(renderer)
                images += imgs
                self.render_s += seconds
        except BrokenProcessPool:  # a worker died (a driver crash): draw them here, where errors are seen
            self.note = "a rendering worker died; rendering in this process"
            return None
        self.note = next((n for n in notes if n), None)
        if len(used) > 1:  # workers disagree on what starts here: draw them all with the one that always does
            self.settings = replace(self.settings, renderer="tiny")
            self.note = "EGL rendering started in some workers only; rendering with TinyRenderer"
            return None
        self.renderer = used.pop() if used else self.renderer
        return images

    def _serial(self) -> list[np.ndarray]:
        t0 = time.perf_counter()
        painter = Painter(self.scene, self.settings, self.arm)
        try:
            images = [painter.draw(s) for s in self.states]
        finally:
            painter.close()
        self.renderer, self.note = painter.renderer, self.note or painter.note
        if self.folder is not None:
            write_pngs(self.folder, 0, images)
        self.render_s += time.perf_counter() - t0
        return images

    def close(self, wait: bool = False) -> None:
        """Stop the workers (idempotent). Without ``wait`` (an error, Ctrl-C: the frames will not be used)
        they are terminated at once rather than left to finish the frames they are drawing."""
        pool, self._pool = self._pool, None
        if pool is None:
            return
        if not wait:
            for proc in list(getattr(pool, "_processes", {}).values()):  # no public way before Python 3.14
                proc.terminate()
        pool.shutdown(wait=True, cancel_futures=True)
