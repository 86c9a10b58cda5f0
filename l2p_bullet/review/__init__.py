"""People in the loop: a web app that collects grades of runs into a SQLite database, and the report.

- runs.py      run folders: identity, trajectory sha256, what can be shown
- schema.py    the database's numbered migrations
- store.py     answers in and out; :func:`~l2p_bullet.review.store.load_grades` (torch- and web-free)
- queue.py     the order runs are shown in, and the checks before an answer is stored
- app.py       the FastAPI app (and static/ the page); server.py runs it with uvicorn
- original.py  the 2018 study's grades, imported
- stats.py, report.py, plots.py   the evaluation's tables and plots

Nothing here is imported by ``perform``; FastAPI and uvicorn only by app.py and server.py.
"""
