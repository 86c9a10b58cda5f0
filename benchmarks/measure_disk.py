"""Which workspace disks every shipped arm reaches once its reach ring cuts them (docs/arms.md, 2026-11-27).

For each arm and radius R (argv, metres; default 0.30 0.35 0.38): the disk of radius R about the table's centre
cut by the arm's ring; its probes (``arm_measure.region_probes``: 5 mm in from every edge, along every arc, at the
corners, the centre) and a 2 cm grid of its inside (5 mm in), each asked pointing down at both
``REACH_HEIGHTS`` with the wrist at 0 and turned either way as ``measure_reach`` turns it. Prints per arm and R
the probes, how many are not reached (and a few of them), the region's area. About a minute on one core.

    .venv/bin/python benchmarks/measure_disk.py 0.30 0.35 0.38
"""

from __future__ import annotations

import sys
import time

import numpy as np


def main(radii: list[float]) -> None:
    from l2p_bullet.core.workspace import Workspace
    from l2p_bullet.embodiment import arm_measure
    from l2p_bullet.embodiment.sim.robot import Kinematics
    from l2p_bullet.plugins import arms as ap

    for name in ("panda", "xarm6", "kuka-iiwa"):
        spec = ap.get(name)
        kin = Kinematics(spec, spec.mount)
        base = np.asarray(spec.mount[:2], float)
        try:
            for radius in radii:
                t = time.time()
                ws = Workspace(radius=radius, ring=(float(base[0]), float(base[1]), *map(float, spec.reach)))
                g = np.arange(-radius, radius + 1e-9, 0.02)
                gx, gy = np.meshgrid(g, g)
                grid = np.column_stack([gx.ravel(), gy.ravel()])
                pts = np.unique(
                    np.round(np.vstack([arm_measure.region_probes(ws), grid[ws.contains(grid, 0.005)]]), 4), axis=0
                )
                bad = [(round(x, 3), round(y, 3)) for x, y in arm_measure.unreached(kin, spec, pts)]
                print(f"{name} R={radius}: ring {spec.reach} from ({base[0]}, {base[1]}); {len(pts)} probes, "
                      f"{len(bad)} unreached {bad[:5]}; area {ws.area():.4f} m^2 ({time.time() - t:.0f} s)", flush=True)
        finally:
            kin.close()


if __name__ == "__main__":
    main([float(r) for r in sys.argv[1:]] or [0.30, 0.35, 0.38])
