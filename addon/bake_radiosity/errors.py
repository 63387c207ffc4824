"""The bake's own error, in a module of its own so that every step (export, lamps, solve) can
raise it without importing the pipeline."""


class BakeError(RuntimeError):
    """A bake that cannot run; the message says why in words an artist can act on."""
