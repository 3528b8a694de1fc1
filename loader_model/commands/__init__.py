"""Subcommands of the ``loader-model`` command line (see :mod:`loader_model.cli`)."""
