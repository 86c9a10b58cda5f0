"""The web plumbing the review app (``review/``) and the teach page (``teach/``) share.

- ``apps``: a FastAPI app that answers only loopback hosts, JSON errors instead of tracebacks, the
  static page of a package;
- ``server``: running such an app with uvicorn on a socket bound here (foreground or a thread).
The web stack (FastAPI, uvicorn) is an import of these modules: the commands import them inside their
bodies, so ``l2p-bullet --help`` does not load it.
"""
