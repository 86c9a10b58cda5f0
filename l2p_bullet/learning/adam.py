"""Adam (AdamW with weight decay) and a cosine decay of its learning rate: torch's own update and schedule, without
``torch.optim``'s Optimizer and scheduler classes.

Why: an ``torch.optim.Optimizer`` imports ``torch._dynamo`` when it is made and again at every step (its methods are
wrapped so that ``torch.compile`` leaves them alone), 1.2 s of CPU in every Python that trains: ``train``, a plugin's
training, the teach page's first training, each benchmark. Nothing here is compiled, so those wrappers do nothing but
that import. The update is torch's functional ``torch.optim.adam.adam``, called with the arguments
``torch.optim.Adam.step`` passes it (state made as its ``_init_group`` makes it), and the schedule is
``CosineAnnealingLR``'s own recursive form: the weights trained are the same bits
(tests/learning/test_adam.py trains side by side with torch's classes).
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import torch
from torch.optim.adam import adam


class Adam:
    """``torch.optim.Adam(params, lr)``, or ``torch.optim.AdamW(params, lr, weight_decay=...)`` with ``decoupled``:
    one parameter group, default betas and eps, no amsgrad. ``lr`` is read at every step (:class:`CosineDecay`
    sets it)."""

    def __init__(self, params: Iterable[torch.Tensor], lr: float, weight_decay: float = 0.0, decoupled: bool = False,
                 betas: tuple[float, float] = (0.9, 0.999), eps: float = 1e-8) -> None:
        self.params = list(params)
        self.lr, self.weight_decay, self.decoupled, self.betas, self.eps = lr, weight_decay, decoupled, betas, eps
        self.state: dict[int, tuple[torch.Tensor, torch.Tensor, torch.Tensor]] = {}
        """Per parameter (its index): the step count, the averages of the gradient and of its square."""

    def zero_grad(self) -> None:
        """As ``Optimizer.zero_grad()``: the gradients dropped (set to None), not zeroed."""
        for p in self.params:
            p.grad = None

    @torch.no_grad()
    def step(self) -> None:
        """One update of every parameter that has a gradient."""
        params, grads, avgs, squares, steps = [], [], [], [], []
        for i, p in enumerate(self.params):
            if p.grad is None:
                continue
            if i not in self.state:  # made lazily, as torch makes it: a CPU scalar step, zeros like the parameter
                scalar = torch.float64 if torch.get_default_dtype() == torch.float64 else torch.float32
                self.state[i] = (torch.tensor(0.0, dtype=scalar, device="cpu"),
                                 torch.zeros_like(p, memory_format=torch.preserve_format),
                                 torch.zeros_like(p, memory_format=torch.preserve_format))
            step, avg, square = self.state[i]
            params.append(p)
            grads.append(p.grad)
            avgs.append(avg)
            squares.append(square)
            steps.append(step)
        adam(params, grads, avgs, squares, [], steps, amsgrad=False, has_complex=any(map(torch.is_complex, params)),
             beta1=self.betas[0], beta2=self.betas[1], lr=self.lr, weight_decay=self.weight_decay, eps=self.eps,
             maximize=False, foreach=None, capturable=False, differentiable=False, fused=None, grad_scale=None,
             found_inf=None, decoupled_weight_decay=self.decoupled)


class CosineDecay:
    """``torch.optim.lr_scheduler.CosineAnnealingLR(opt, T_max=t_max)`` (down to 0), stepped once per epoch after the
    epoch's updates: its recursive form, so the rates are the same floats."""

    def __init__(self, opt: Adam, t_max: int, eta_min: float = 0.0) -> None:
        self.opt, self.t_max, self.eta_min = opt, t_max, eta_min
        self.base_lr = opt.lr
        self.last_epoch = 0

    def step(self) -> None:
        self.last_epoch += 1
        e, t, lr = self.last_epoch, self.t_max, self.opt.lr
        if (e - 1 - t) % (2 * t) == 0:
            self.opt.lr = lr + (self.base_lr - self.eta_min) * (1 - math.cos(math.pi / t)) / 2
        else:
            self.opt.lr = ((1 + math.cos(math.pi * e / t)) / (1 + math.cos(math.pi * (e - 1) / t))
                           * (lr - self.eta_min) + self.eta_min)
