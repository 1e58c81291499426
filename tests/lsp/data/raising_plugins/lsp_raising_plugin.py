"""A plugin whose registration hook raises (tests/lsp: the server must go on)."""


def orccad_register_control_laws(register):
    raise RuntimeError("this plugin is broken on purpose")
