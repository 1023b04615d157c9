"""Scene files (TOML): a scene and how to run it, read and written without running code.

The public face of ``shroudnet.io.scenefile`` (where the layout of a file is documented):
every name a user calls, under the path it has always had.
"""

from .io.scenefile import Laws as Laws
from .io.scenefile import RunSettings as RunSettings
from .io.scenefile import SceneAt as SceneAt
from .io.scenefile import SceneFile as SceneFile
from .io.scenefile import SceneFileError as SceneFileError
from .io.scenefile import document as document
from .io.scenefile import dumps as dumps
from .io.scenefile import is_substructure as is_substructure
from .io.scenefile import load as load
from .io.scenefile import read as read
from .io.scenefile import save as save
from .io.scenefile import with_value as with_value

__all__ = ["Laws", "RunSettings", "SceneAt", "SceneFile", "SceneFileError", "document",
           "dumps", "is_substructure", "load", "read", "save", "with_value"]
