"""QGIS plugin: the rock hatching Processing provider."""


def classFactory(iface):  # noqa: N802 (QGIS's name)
    from .plugin import RockhatchPlugin
    return RockhatchPlugin(iface)
