// The dry-run result returned by `partscope/dryRun` and the `partscope.dryRun` command, and
// plain-text formatting of it. Kept free of the `vscode` module so it can be unit-tested in node.

export type SegmentKind = "rapid" | "feed" | "arc";

export interface ToolpathSegment {
  kind: SegmentKind;
  /** 0-based source line of the block that produced the move. */
  line: number;
  /** mm/min; 0 for rapids. */
  feed: number;
  tool: number;
  points: [number, number, number][];
  /** A decimated segment of several motions: the 0-based line of the motion each point ends. */
  lines?: number[];
}

/** How the server simplified the toolpath (`partscope/dryRun`'s `decimation`). */
export interface Decimation {
  tolerance_mm: number;
  requested_tolerance_mm: number;
  max_points: number;
  motions: number;
  points_in: number;
  points_out: number;
  points_dropped: number;
  segments_out: number;
  decimated: boolean;
  capped: boolean;
  truncated_at_line: number | null;
}

export interface DryRunResult {
  version: number;
  cycle_time_s: number;
  motion_s: number;
  rapid_s: number;
  cutting_s: number;
  dwell_s: number;
  tool_change_s: number;
  distance_mm: number;
  toolpath: {
    segments: ToolpathSegment[];
    bounds: { min: [number, number, number]; max: [number, number, number] };
  };
  diagnostics: unknown[];
  /** False when the run stopped before the program's end: the times cover only what ran. */
  complete?: boolean;
  /** Where and why the run stopped (0-based line), `null` when complete. */
  stopped_at?: { line: number; reason: string } | null;
  decimation?: Decimation;
}

/** "stopped at line N: reason" (1-based line) for a run that stopped early, else undefined. */
export function stoppedText(r: DryRunResult): string | undefined {
  if (r.complete !== false || !r.stopped_at) return undefined;
  return `stopped at line ${r.stopped_at.line + 1}: ${r.stopped_at.reason}`;
}

/** `h:mm:ss` above an hour, `m:ss.s` below: what a machinist reads off a control's timer. */
export function formatDuration(seconds: number): string {
  if (typeof seconds !== "number" || !Number.isFinite(seconds)) return "–";
  const neg = seconds < 0;
  const abs = Math.abs(seconds);
  let text: string;
  // Round once, in the unit shown, so that 59.96 s prints as 1:00.0 and not 0:60.0.
  if (abs < 3599.95) {
    const tenths = Math.round(abs * 10);
    const m = Math.floor(tenths / 600);
    const rest = (tenths - m * 600) / 10;
    text = `${m}:${rest.toFixed(1).padStart(4, "0")}`;
  } else {
    const whole = Math.round(abs);
    const h = Math.floor(whole / 3600);
    const m = Math.floor((whole % 3600) / 60);
    text = `${h}:${String(m).padStart(2, "0")}:${String(whole % 60).padStart(2, "0")}`;
  }
  return (neg ? "-" : "") + text;
}

/** A fixed-width breakdown for the output channel and the status-bar tooltip. */
export function summarize(r: DryRunResult): string {
  const partial = r.complete === false;
  const rows: [string, string][] = [
    ["cycle time", formatDuration(r.cycle_time_s) + (partial ? " (partial)" : "")],
    ["  cutting", formatDuration(r.cutting_s)],
    ["  rapid", formatDuration(r.rapid_s)],
    ["  dwell", formatDuration(r.dwell_s)],
    ["  tool change", formatDuration(r.tool_change_s)],
    ["distance", `${Number.isFinite(r.distance_mm) ? r.distance_mm.toFixed(1) : "–"} mm`],
    ["segments", String(r.toolpath?.segments?.length ?? 0)],
  ];
  const b = r.toolpath?.bounds;
  if (b?.min && b?.max) {
    ["X", "Y", "Z"].forEach((axis, i) => {
      rows.push([`${axis} range`, `${b.min[i].toFixed(3)} … ${b.max[i].toFixed(3)}`]);
    });
  }
  const d = r.decimation;
  if (d?.decimated) {
    rows.push(["toolpath", `${d.points_out} of ${d.points_in} points`]);
    rows.push(["  within", `${d.tolerance_mm.toFixed(3)} mm${d.capped ? " (capped)" : ""}`]);
  }
  const lines = rows.map(([k, v]) => `${k.padEnd(14)}${v.padStart(22)}`);
  if (d?.truncated_at_line !== null && d?.truncated_at_line !== undefined) {
    lines.push(`toolpath cut at line ${d.truncated_at_line + 1} (size cap)`);
  }
  const stopped = stoppedText(r);
  if (stopped) lines.push(stopped);
  return lines.join("\n");
}
