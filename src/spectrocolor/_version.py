"""The package's version, in one place: the package face and the CLI's ``--version`` read it here."""

__version__ = "0.1.0"
