"""The one way in and out: readable input files, checked output paths and atomic writes,
numeric argument checks, and the process hygiene of long commands.

:mod:`~loader_model.io.files` (reading), :mod:`~loader_model.io.export` (writing),
:mod:`~loader_model.io.arrays` (numbers and arrays at entry points). Imports nothing else of
the package.
"""
