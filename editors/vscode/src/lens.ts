// The cycle-time code lens's command (`partscope.showBreakdown`). The language client registers
// the server's commands as VS Code commands, so a click on the lens reaches the client's
// executeCommand middleware, which runs it here. Kept free of the `vscode` module so it can be
// tested in node.

export const BREAKDOWN_COMMAND = "partscope.showBreakdown";

/** The server's answer: the dry run's figures without the toolpath, and the breakdown as text. */
export interface BreakdownResult {
  uri: string;
  version: number;
  cycle_time_s: number | null;
  complete: boolean;
  stopped_at?: { line: number; reason: string } | null;
  /** Cycle time, its split, where the time goes and the top causes, one per line. */
  text: string;
}

/** What a click shows: the breakdown, and the toolpath preview of the lens's document. */
export interface LensActions {
  report(result: BreakdownResult): void;
  preview(uri: string): void | Promise<void>;
}

export type ExecuteNext = (command: string, args: unknown[]) => unknown;

/**
 * The executeCommand middleware: the lens's command asks the server for the breakdown with
 * `show: false` (the report shows it; a server message would repeat it) and opens the preview;
 * every other command goes to the server unchanged.
 */
export async function executeCommand(
  command: string,
  args: unknown[],
  next: ExecuteNext,
  actions: LensActions
): Promise<unknown> {
  if (command !== BREAKDOWN_COMMAND) return next(command, args);
  const result = (await next(command, [args[0] ?? null, { show: false }])) as BreakdownResult;
  actions.report(result);
  await actions.preview(result.uri);
  return result;
}
