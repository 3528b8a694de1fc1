"""Build-time symbolic derivation of the loader model (SymPy). Writes ``generated/``.

Run ``python -m derive --output generated`` (``make regenerate``). The runtime package
``loader_model`` never imports this package or SymPy.
"""
