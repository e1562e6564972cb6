"""The ``persson-fast`` command.

``main`` (the commands ``figure2``, ``contact``, ``info``), ``parser`` (the argument parser),
``config`` (a TOML file and the flags, merged), ``output`` (files written whole or not at all);
``python -m persson_fast.cli`` runs ``main.run``.
"""
