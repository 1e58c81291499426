// The ORCCAD extension: starts `orccad lsp` (stdio) for .orc files, and a command that asks
// the server to prove the open file's properties (the same as saving it).
const vscode = require("vscode");
const { LanguageClient, TransportKind } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const [command, ...args] = vscode.workspace
    .getConfiguration("orccad")
    .get("server.command", ["orccad", "lsp"]);
  const serverOptions = { command, args, transport: TransportKind.stdio };
  const clientOptions = { documentSelector: [{ scheme: "file", language: "orccad" }] };
  client = new LanguageClient("orccad", "ORCCAD", serverOptions, clientOptions);
  context.subscriptions.push(
    vscode.commands.registerCommand("orccad.checkFile", () => {
      const editor = vscode.window.activeTextEditor;
      if (editor && editor.document.languageId === "orccad") {
        client.sendRequest("workspace/executeCommand", {
          command: "orccad.check",
          arguments: [editor.document.uri.toString()],
        });
      }
    })
  );
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
