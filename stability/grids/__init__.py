"""Spectra over parameter grids: atlases as CF-annotated xarray datasets, on netCDF and beyond memory.

Layer 3 (docs/architecture.md): imports the linear layer, the models and the parameters, never
the nonlinear runs, recipes, figures or command line.

* :mod:`~stability.grids.atlases` - :func:`stability.atlas` and what is read off an atlas
  (the time convention, the marginal rule, the leading growth rate);
* :mod:`~stability.grids.netcdf` - atomic netCDF writing and :func:`stability.open_atlas`;
* :mod:`~stability.grids.chunked` - lazy, chunked spectra and chunk-wise writing;
* :mod:`~stability.grids.store` - atlases as Zarr stores written by region, and resuming from them;
* :mod:`~stability.grids.cluster` - where chunks run (this process or a dask cluster);
* :mod:`~stability.grids.ranges` - parameter values written as text (``start:stop:num``).
"""
