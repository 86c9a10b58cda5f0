# Two set-up commands on a fresh machine with Python 3.11 and pip (see README):
#   make demo   installs into .venv and performs "move A around B" on the default scene
#   make demo-row  the same for "make a row of A, B, C and D" (a composite taught by demonstration)
#   make test   installs into .venv and runs the whole test suite
# torch is pinned to 2.13.0 and installed first, so nothing pulls another build. Where pip resolves torch from
# plain PyPI on Linux x86_64 (whose default wheel is the CUDA build, several GB), name PyTorch's CPU index:
#   make install TORCH_INDEX=https://download.pytorch.org/whl/cpu
# (empty by default: the machines this project is built on get the CPU wheel from their pip configuration).
# --no-cache-dir: the environment is 2.5 GB installed; pip's wheel cache would hold another copy of the wheels
# (a CI run ran out of disk during the install).
PYTHON ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
TORCH := torch==2.13.0
TORCH_INDEX ?=

.PHONY: install demo demo-row test lint bench clean

$(VENV)/.installed: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --no-cache-dir --upgrade pip
	$(PY) -m pip install --quiet --no-cache-dir $(TORCH) $(if $(TORCH_INDEX),--index-url $(TORCH_INDEX))
	$(PY) -m pip install --quiet --no-cache-dir -e '.[test,ray,export,rerun]'  # the extras' tests (evaluate --ray local, export) run in CI
	touch $@

install: $(VENV)/.installed

demo: install
	$(VENV)/bin/l2p-bullet perform "move A around B" --force --out runs/demo

demo-row: install  # the composite taught on the teach page: a row of four blocks (docs/perform.md)
	$(VENV)/bin/l2p-bullet perform "make a row of A, B, C and D" --scene examples/four_blocks.json --force --out runs/demo-row

# pytest-xdist: one worker per core; --dist loadgroup keeps each test module on one worker (its shared
# fixtures are made once), see tests/conftest.py
test: lint
	$(PY) -m pytest -q -n auto --dist loadgroup

lint: install
	$(VENV)/bin/ruff check l2p_bullet research tests benchmarks examples

bench: install  # every benchmark at its default size: hours on 2 cores (docs/benchmarks.md)
	for b in benchmarks/bench_*.py; do $(PY) $$b || exit 1; done

# Build outputs only. runs/ is not touched: it holds what people made (review answers in runs/reviews.sqlite,
# trained bundles in runs/bundles/, evaluations, recorded runs); delete what you no longer want by hand.
clean:
	rm -rf $(VENV) build dist *.egg-info

# Re-train the five built-in action bundles into l2p_bullet/actions/ (minutes on 2 cores): each progress
# model on the demonstrations, then each action's REINFORCE move policy against it (issue 4). Feedback
# (--feedback original, --feedback-judge rules) is not used: cross-validated it did not raise agreement
# with people, and the rule-judge feedback cost planning success (docs/learning.md, "Feedback").
.PHONY: bundles
bundles: install
	for a in closer away next-to past around; do \
	  nice -n 10 $(VENV)/bin/l2p-bullet train $$a --seed 0 --force --out l2p_bullet/actions/$$(echo $$a | tr - _) || exit 1; \
	done
	for a in closer away next-to past around; do \
	  nice -n 10 $(VENV)/bin/l2p-bullet train-policy $$a --seed 0 --bundle l2p_bullet/actions/$$(echo $$a | tr - _) --force || exit 1; \
	done
	# the row composite's recipe is learned by recognising its demonstrations with these actions: re-learn it
	$(VENV)/bin/python -c "from l2p_bullet.composite.bundle import read_demos, write_recipe; \
	  from l2p_bullet.composite.recipe import learn; from l2p_bullet.recognition import recognisers; \
	  write_recipe('l2p_bullet/actions/row', learn(read_demos('l2p_bullet/actions/row'), recognisers()[0]))"
