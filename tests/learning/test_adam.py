"""The trainers' Adam and cosine decay (learning/adam.py) against torch.optim's classes: the same weights to the bit.
That a Python that trains imports no ``torch._dynamo`` is checked on a ``train`` process of
tests/test_determinism_audit.py."""

from __future__ import annotations

import pytest
import torch

from l2p_bullet.learning.adam import Adam, CosineDecay
from l2p_bullet.learning.progress_net import ProgressNet


def _train(make, epochs: int, steps: int, seed: int = 0) -> tuple[list[torch.Tensor], list[float]]:
    """A progress net trained ``epochs`` x ``steps`` on fixed random batches, the rate decayed once per epoch; some
    steps leave a parameter without a gradient (Adam skips it). The weights and the rate after each epoch."""
    torch.manual_seed(seed)
    net = ProgressNet(6, 8)
    opt, sched, rate = make(net)
    g = torch.Generator().manual_seed(seed + 1)
    rates = []
    for _ in range(epochs):
        for k in range(steps):
            x, y = torch.randn(3, 5, 6, generator=g), torch.rand(3, 5, generator=g)
            loss = ((net(x) - y) ** 2).mean()
            opt.zero_grad()
            loss.backward()
            torch.nn.utils.clip_grad_norm_(net.parameters(), 1.0)
            if k == 1:  # a parameter without a gradient this step
                next(net.parameters()).grad = None
            opt.step()
        if sched is not None:
            sched.step()
        rates.append(rate(opt))
    return [p.detach().clone() for p in net.parameters()], rates


CASES = {  # how the trainers make them (optimise.py, train_policy.py): ours, torch's
    "adam, cosine": (lambda n: (o := Adam(n.parameters(), lr=3e-3), CosineDecay(o, 7), lambda o: o.lr),
                     lambda n: (o := torch.optim.Adam(n.parameters(), lr=3e-3),
                                torch.optim.lr_scheduler.CosineAnnealingLR(o, T_max=7),
                                lambda o: o.param_groups[0]["lr"])),
    "adamw, cosine": (lambda n: (o := Adam(n.parameters(), lr=3e-3, weight_decay=0.01, decoupled=True),
                                 CosineDecay(o, 7), lambda o: o.lr),
                      lambda n: (o := torch.optim.AdamW(n.parameters(), lr=3e-3, weight_decay=0.01),
                                 torch.optim.lr_scheduler.CosineAnnealingLR(o, T_max=7),
                                 lambda o: o.param_groups[0]["lr"])),
    "adam, no decay": (lambda n: (Adam(n.parameters(), lr=1e-2), None, lambda o: o.lr),
                       lambda n: (torch.optim.Adam(n.parameters(), lr=1e-2), None, lambda o: o.param_groups[0]["lr"])),
}


@pytest.mark.parametrize("case", list(CASES))
def test_the_weights_and_rates_are_torch_optims_to_the_bit(case):
    ours, theirs = CASES[case]
    epochs = 9  # past T_max = 7: the schedule's rising branch too
    (w1, r1), (w2, r2) = _train(ours, epochs, 4), _train(theirs, epochs, 4)
    assert r1 == r2
    assert all(torch.equal(a, b) for a, b in zip(w1, w2, strict=True))
    assert not all(torch.equal(a, b) for a, b in zip(w1, _train(ours, 1, 1)[0], strict=True))  # it did train

