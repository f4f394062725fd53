"""The SPECTRA explorer: a local web app for Sällström's five settings (seed 002).

``create_app()`` (in :mod:`.server`) builds the FastAPI application; ``spectrocolor app``
serves it on 127.0.0.1. Needs the ``app`` extra (FastAPI, uvicorn).
"""
