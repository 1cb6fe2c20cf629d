"""The plugin's icon, for the provider and its algorithms."""
import os

from qgis.PyQt.QtGui import QIcon

ICON = os.path.join(os.path.dirname(__file__), "icon.svg")


class WithIcon:
    """icon() and svgIconPath() of a provider or an algorithm."""

    def icon(self):
        return QIcon(ICON)

    def svgIconPath(self):  # noqa: N802 (QGIS's name)
        return ICON
