"""The chunked route: volumes larger than memory, read and processed a block at a time (threads or a Dask cluster)."""
