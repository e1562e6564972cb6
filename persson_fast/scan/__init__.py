"""Parameter scans: many scenes, each swept over the same nominal pressures.

``api`` (the function :func:`persson_fast.scan`), ``grid`` (the scene grid checked and
crossed), ``run`` (one scene, a chunk, threads or a dask cluster), ``results`` (the dataset and
the failure warning).
"""
