"""The teach page: record demonstrations of a new preposition in the browser, train it, watch it performed.

``l2p-bullet teach ACTION`` serves it the way ``l2p-bullet review`` serves the review app (FastAPI, the
review app's uvicorn runner ``web/server.py`` on 127.0.0.1, static HTML/JS in ``static/``);
:mod:`.lesson` holds everything that is not web (scenes, validation, the demos file, training).
"""
