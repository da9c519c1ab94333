"""3D volumes (CT scans): medial voxels and mid-surfaces of thin-plate parts.

:func:`midsurface_medial_axis` (``method="midsurface"``) implements Kumar,
Michikawa and Suzuki, "Improving medial surfaces for reverse engineering"
(docs/references.md); :func:`medial_voxel_axis` (``method="voxels"``) returns the
medial voxels. Both are reached through :func:`medialaxis.medial_axis`.
"""

from medialaxis.volume.files.readers import read_volume
from medialaxis.volume.inputs import VolumeInput, load_volume
from medialaxis.volume.pipeline import VolumeStages, midsurface_medial_axis, volume_stages
from medialaxis.volume.voxel_axis import medial_voxel_axis

__all__ = [
    "midsurface_medial_axis",
    "medial_voxel_axis",
    "volume_stages",
    "VolumeStages",
    "load_volume",
    "VolumeInput",
    "read_volume",
]
