"""The bundled case files (``*.toml``) and film maps (``maps/*.npz``): package data of ``lubedyn``."""
