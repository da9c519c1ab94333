"""Volume files: whole-volume readers and sources read block by block (NRRD, NIfTI, TIFF, DICOM, raw, Zarr, OME-Zarr)."""
