"""The language server (``orccad lsp``): the plan language in every editor.

Built on the compiler pipeline (:mod:`orccad_app.pipeline`), the checker
(:mod:`orccad_app.verify`) and the plugin host; speaks the protocol with pygls (the optional
extra ``lsp``). One module per feature: :mod:`.analysis` (a document through the pipeline),
:mod:`.problems` (diagnostics), :mod:`.symbols` (outline, folding), :mod:`.hover`,
:mod:`.navigation` (definition, references), :mod:`.completion`, :mod:`.proof` (the
verdicts of ``orccad check`` in the editor); :mod:`.server` keeps the documents and
:mod:`.features` wires the protocol to them. See ``docs/editors.md``.
"""

__all__: list[str] = []
