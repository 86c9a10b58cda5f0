"""l2p-bullet: teach a simulated robot arm spatial actions from human demonstrations.

Kept import-light on purpose: ``l2p-bullet --help`` must not import torch or pybullet.
"""

__version__ = "0.1.0"
