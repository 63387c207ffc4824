"""Bake Radiosity's native core (_core) for the Blender add-on, with the libraries it needs beside it."""
