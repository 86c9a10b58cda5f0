"""l2p-bullet: teach a simulated robot arm spatial actions from human demonstrations.

Kept import-light on purpose: ``l2p-bullet --help`` must not import torch or pybullet. Importing the
package changes nothing in the process (no signal handler, no environment): the command line's own
start-up lives in :mod:`l2p_bullet.launch`, the console script's entry point.
"""

__version__ = "0.1.0"
