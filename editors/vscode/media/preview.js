// Partscope toolpath preview.
//
// A dependency-free canvas renderer for the `toolpath` part of a Partscope dry-run result.
// The same file runs inside the VS Code webview and in a plain browser page (preview.html),
// so it talks to its host only through `post()` and `window` "message" events:
//
//   host -> preview   { type: "data", data: <dry-run result>, title?: string }
//                     { type: "cursor", line: <0-based line or null> }
//                     { type: "error", message: string }
//   preview -> host   { type: "ready" }
//                     { type: "reveal", line: <0-based line> }
//
// In a plain browser (no `acquireVsCodeApi`), posted messages are appended to
// `window.partscopeOutbox` and dispatched as a `partscope-post` CustomEvent, and
// `preview.html?sample=<url>` loads a dry-run JSON file directly. A page written by
// `partscope run --html` holds `{data, title}` in `<script type="application/json"
// id="partscope-data">` and shows it at once.
(function (global) {
  "use strict";

  var DEG = Math.PI / 180;
  // Named views. Pitch 0 looks straight down the Z axis (the usual plan view of a mill);
  // pitch 90 looks horizontally, so Z points up the screen.
  var VIEWS = {
    top: { yaw: 0, pitch: 0 },
    front: { yaw: 0, pitch: 90 * DEG },
    side: { yaw: -90 * DEG, pitch: 90 * DEG },
    iso: { yaw: -45 * DEG, pitch: 54.7356 * DEG },
  };
  // Feed colour ramp: slow feeds blue, fast feeds red, as on most CAM verifiers.
  var RAMP = [
    [43, 131, 255],
    [0, 200, 220],
    [60, 210, 80],
    [250, 220, 40],
    [240, 60, 40],
  ];
  var BUCKETS = 32;
  var HIT_RADIUS_PX = 6;

  function rampColour(t) {
    if (!(t >= 0)) t = 0;
    if (t > 1) t = 1;
    var x = t * (RAMP.length - 1);
    var i = Math.min(RAMP.length - 2, Math.floor(x));
    var f = x - i;
    var a = RAMP[i];
    var b = RAMP[i + 1];
    var c = [0, 1, 2].map(function (k) {
      return Math.round(a[k] + (b[k] - a[k]) * f);
    });
    return "rgb(" + c[0] + "," + c[1] + "," + c[2] + ")";
  }

  // Same format as the status bar (src/dryrun.ts): m:ss.s below an hour, h:mm:ss above.
  function formatDuration(s) {
    if (typeof s !== "number" || !isFinite(s)) return "–";
    var abs = Math.abs(s);
    var text;
    if (abs < 3599.95) {
      var tenths = Math.round(abs * 10);
      var m = Math.floor(tenths / 600);
      var rest = ((tenths - m * 600) / 10).toFixed(1);
      text = m + ":" + (rest.length < 4 ? "0" : "") + rest;
    } else {
      var whole = Math.round(abs);
      var h = Math.floor(whole / 3600);
      var mm = Math.floor((whole % 3600) / 60);
      var ss = whole % 60;
      text = h + ":" + (mm < 10 ? "0" : "") + mm + ":" + (ss < 10 ? "0" : "") + ss;
    }
    return (s < 0 ? "-" : "") + text;
  }

  function distToSegmentSq(px, py, ax, ay, bx, by) {
    var dx = bx - ax;
    var dy = by - ay;
    var len = dx * dx + dy * dy;
    var t = len > 0 ? ((px - ax) * dx + (py - ay) * dy) / len : 0;
    if (t < 0) t = 0;
    else if (t > 1) t = 1;
    var cx = ax + t * dx - px;
    var cy = ay + t * dy - py;
    return cx * cx + cy * cy;
  }

  /**
   * @param {HTMLCanvasElement} canvas
   * @param {{ background?: string, onReveal?: (line: number) => void, onHover?: (seg: object|null, x: number, y: number) => void }} [options]
   */
  function Preview(canvas, options) {
    this.canvas = canvas;
    this.ctx = canvas.getContext("2d");
    this.options = options || {};
    this.background = this.options.background || "#1e1e1e";
    this.segments = [];
    // World coordinates of every point of every segment, flattened (x, y, z, x, y, z, ...).
    this.world = new Float64Array(0);
    // Screen coordinates from the last draw, flattened (x, y, ...), in CSS pixels.
    this.screen = new Float32Array(0);
    this.offsets = [];
    this.buckets = [];
    this.center = [0, 0, 0];
    this.bounds = null;
    this.feedRange = [0, 0];
    this.yaw = VIEWS.iso.yaw;
    this.pitch = VIEWS.iso.pitch;
    this.scale = 1;
    this.panX = 0;
    this.panY = 0;
    this.cursorLine = null;
    this.showRapids = true;
    this.width = 0;
    this.height = 0;
    this._frame = 0;
    this._installInput();
  }

  // A decimated segment holds several motions: `lines[j]` is the 0-based line of the motion
  // that ends at point j. Split into one segment per line, so hover, click and the cursor
  // highlight still work block by block.
  function splitRuns(segs) {
    var out = [];
    for (var i = 0; i < segs.length; i++) {
      var s = segs[i];
      var pts = s.points || [];
      if (!Array.isArray(s.lines) || s.lines.length !== pts.length || pts.length < 2) {
        out.push(s);
        continue;
      }
      var j = 1;
      while (j < pts.length) {
        var line = s.lines[j];
        var piece = [pts[j - 1]];
        while (j < pts.length && s.lines[j] === line) piece.push(pts[j++]);
        out.push({ kind: s.kind, line: line, feed: s.feed, tool: s.tool, points: piece });
      }
    }
    return out;
  }

  Preview.prototype.setData = function (result) {
    var toolpath = (result && result.toolpath) || { segments: [] };
    var segs = splitRuns(Array.isArray(toolpath.segments) ? toolpath.segments : []);
    var total = 0;
    for (var i = 0; i < segs.length; i++) total += (segs[i].points || []).length;
    var world = new Float64Array(total * 3);
    var offsets = new Array(segs.length);
    var k = 0;
    var minFeed = Infinity;
    var maxFeed = -Infinity;
    var lo = [Infinity, Infinity, Infinity];
    var hi = [-Infinity, -Infinity, -Infinity];
    for (i = 0; i < segs.length; i++) {
      var s = segs[i];
      offsets[i] = k / 3;
      var pts = s.points || [];
      for (var j = 0; j < pts.length; j++) {
        for (var a = 0; a < 3; a++) {
          var v = Number(pts[j][a]) || 0;
          world[k++] = v;
          if (v < lo[a]) lo[a] = v;
          if (v > hi[a]) hi[a] = v;
        }
      }
      if (s.kind !== "rapid" && typeof s.feed === "number" && s.feed > 0) {
        if (s.feed < minFeed) minFeed = s.feed;
        if (s.feed > maxFeed) maxFeed = s.feed;
      }
    }
    offsets.push(total);
    if (toolpath.bounds && toolpath.bounds.min && toolpath.bounds.max) {
      lo = toolpath.bounds.min.slice(0, 3).map(Number);
      hi = toolpath.bounds.max.slice(0, 3).map(Number);
    }
    if (!isFinite(lo[0])) {
      lo = [0, 0, 0];
      hi = [0, 0, 0];
    }
    if (!isFinite(minFeed)) {
      minFeed = 0;
      maxFeed = 0;
    }
    this.result = result || {};
    this.segments = segs;
    this.world = world;
    this.screen = new Float32Array(total * 2);
    this.offsets = offsets;
    this.bounds = { min: lo, max: hi };
    this.center = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2];
    this.feedRange = [minFeed, maxFeed];
    this._dataVersion = (this._dataVersion || 0) + 1;
    this.buckets = segs.map(function (s) {
      if (s.kind === "rapid") return -1;
      if (maxFeed <= minFeed) return BUCKETS - 1;
      return Math.round(((s.feed - minFeed) / (maxFeed - minFeed)) * (BUCKETS - 1));
    });
    this.fit();
  };

  Preview.prototype.setCursorLine = function (line) {
    var next = typeof line === "number" ? line : null;
    if (next === this.cursorLine) return;
    this.cursorLine = next;
    this.requestDraw();
  };

  Preview.prototype.setView = function (name) {
    var v = VIEWS[name];
    if (!v) return;
    this.yaw = v.yaw;
    this.pitch = v.pitch;
    this.fit();
  };

  Preview.prototype.setShowRapids = function (show) {
    this.showRapids = !!show;
    this.requestDraw();
  };

  // Rotation into view space: x right, y up the screen, z towards the viewer.
  Preview.prototype._basis = function () {
    var cy = Math.cos(this.yaw);
    var sy = Math.sin(this.yaw);
    var cp = Math.cos(this.pitch);
    var sp = Math.sin(this.pitch);
    return { cy: cy, sy: sy, cp: cp, sp: sp };
  };

  /** Projects a world point to CSS pixels on the canvas. */
  Preview.prototype.project = function (p) {
    var b = this._basis();
    var x = p[0] - this.center[0];
    var y = p[1] - this.center[1];
    var z = p[2] - this.center[2];
    var x1 = x * b.cy - y * b.sy;
    var y1 = x * b.sy + y * b.cy;
    var up = y1 * b.cp + z * b.sp;
    return [this.width / 2 + this.panX + this.scale * x1, this.height / 2 + this.panY - this.scale * up];
  };

  Preview.prototype._resize = function () {
    var dpr = global.devicePixelRatio || 1;
    var w = this.canvas.clientWidth || this.canvas.width;
    var h = this.canvas.clientHeight || this.canvas.height;
    if (w !== this.width || h !== this.height || this.canvas.width !== Math.round(w * dpr)) {
      this.width = w;
      this.height = h;
      this.canvas.width = Math.round(w * dpr);
      this.canvas.height = Math.round(h * dpr);
    }
    this.ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  };

  /** Zooms and pans so the whole toolpath (its bounding box) fills the canvas. */
  Preview.prototype.fit = function () {
    this._resize();
    var lo = this.bounds ? this.bounds.min : [0, 0, 0];
    var hi = this.bounds ? this.bounds.max : [0, 0, 0];
    var saveScale = this.scale;
    this.scale = 1;
    this.panX = 0;
    this.panY = 0;
    var minX = Infinity;
    var maxX = -Infinity;
    var minY = Infinity;
    var maxY = -Infinity;
    for (var i = 0; i < 8; i++) {
      var p = this.project([i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]]);
      minX = Math.min(minX, p[0]);
      maxX = Math.max(maxX, p[0]);
      minY = Math.min(minY, p[1]);
      maxY = Math.max(maxY, p[1]);
    }
    var ex = maxX - minX;
    var ey = maxY - minY;
    // Keep the toolpath clear of the statistics panel (left) and the legend (right) when
    // the canvas is wide enough to afford it.
    var inset = this.width > 700 ? { l: 250, r: 40, t: 24, b: 40 } : { l: 16, r: 16, t: 16, b: 16 };
    var aw = Math.max(50, this.width - inset.l - inset.r);
    var ah = Math.max(50, this.height - inset.t - inset.b);
    var sx = ex > 1e-9 ? aw / ex : Infinity;
    var sy = ey > 1e-9 ? ah / ey : Infinity;
    var s = Math.min(sx, sy);
    if (!isFinite(s) || s <= 0) s = saveScale > 0 && isFinite(saveScale) ? saveScale : 1;
    // Screen offset of the fit area's centre from the canvas centre.
    var ax = inset.l + aw / 2 - this.width / 2;
    var ay = inset.t + ah / 2 - this.height / 2;
    var cx = (minX + maxX) / 2 - this.width / 2;
    var cy = (minY + maxY) / 2 - this.height / 2;
    this.scale = s;
    this.panX = ax - cx * s;
    this.panY = ay - cy * s;
    this.requestDraw();
  };

  // Marks the view as moving: big toolpaths draw coarsely until it settles.
  Preview.prototype._interact = function () {
    var self = this;
    if (this.world.length / 3 < 50000) return;
    this._coarse = true;
    clearTimeout(this._settle);
    this._settle = setTimeout(function () {
      self._coarse = false;
      self.requestDraw();
    }, SETTLE_MS);
  };

  Preview.prototype.requestDraw = function () {
    var self = this;
    if (this._frame) return;
    var raf = global.requestAnimationFrame || function (f) {
      return setTimeout(f, 16);
    };
    this._frame = raf(function () {
      self._frame = 0;
      self.draw();
    });
  };

  Preview.prototype._projectAll = function () {
    var b = this._basis();
    var w = this.world;
    var out = this.screen;
    var n = w.length / 3;
    var ox = this.width / 2 + this.panX;
    var oy = this.height / 2 + this.panY;
    var s = this.scale;
    var c0 = this.center[0];
    var c1 = this.center[1];
    var c2 = this.center[2];
    for (var i = 0; i < n; i++) {
      var x = w[3 * i] - c0;
      var y = w[3 * i + 1] - c1;
      var z = w[3 * i + 2] - c2;
      var x1 = x * b.cy - y * b.sy;
      var y1 = x * b.sy + y * b.cy;
      out[2 * i] = ox + s * x1;
      out[2 * i + 1] = oy - s * (y1 * b.cp + z * b.sp);
    }
  };

  // Adds segment `seg` to the current path. Consecutive segments that continue where the last
  // one ended extend the same polyline, and points closer than MIN_STEP_PX to the last emitted
  // point are skipped: CAM programs are mostly sub-pixel moves, and rasterising each of them
  // as its own sub-path is what makes big toolpaths slow.
  var MIN_STEP_PX = 0.75;
  // While the user drags or zooms a big toolpath, a coarser step keeps frames fast; the full
  // drawing follows once the view has been still for SETTLE_MS.
  var COARSE_STEP_PX = 3;
  var SETTLE_MS = 160;
  Preview.prototype._tracePath = function (ctx, seg, pen) {
    var scr = this.screen;
    var a = this.offsets[seg];
    var e = this.offsets[seg + 1];
    if (e - a < 1) return;
    var x = scr[2 * a];
    var y = scr[2 * a + 1];
    var dx = x - pen.x;
    var dy = y - pen.y;
    if (!pen.down || dx * dx + dy * dy > 0.25) {
      ctx.moveTo(x, y);
      pen.x = x;
      pen.y = y;
      pen.down = true;
      if (e - a === 1) {
        ctx.lineTo(x + 0.01, y);
        return;
      }
    }
    var step = this._coarse ? COARSE_STEP_PX : MIN_STEP_PX;
    var min2 = step * step;
    var emitted = false;
    for (var i = a + 1; i < e; i++) {
      x = scr[2 * i];
      y = scr[2 * i + 1];
      dx = x - pen.x;
      dy = y - pen.y;
      // A segment's last point is kept if nothing of the segment was drawn yet, so every move
      // leaves at least a dot.
      if (dx * dx + dy * dy < min2 && (i + 1 < e || emitted)) continue;
      ctx.lineTo(x, y);
      pen.x = x;
      pen.y = y;
      emitted = true;
    }
  };

  function newPen() {
    return { x: 0, y: 0, down: false };
  }

  // Everything but the cursor highlight and the axis triad is drawn into an offscreen canvas
  // that is reused while the view and the data stay the same, so following the editor's
  // cursor through a big program costs one image copy per move instead of a full redraw.
  Preview.prototype.draw = function () {
    this._resize();
    var dpr = global.devicePixelRatio || 1;
    var key = [
      this.canvas.width, this.canvas.height, this.yaw, this.pitch, this.scale, this.panX, this.panY,
      this.showRapids, !!this._coarse, this._dataVersion, this.background,
    ].join(",");
    if (!this._base || key !== this._baseKey) {
      if (!this._base) this._base = document.createElement("canvas");
      this._base.width = this.canvas.width;
      this._base.height = this.canvas.height;
      var bctx = this._base.getContext("2d");
      bctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      this._drawBase(bctx);
      this._baseKey = key;
    }
    var ctx = this.ctx;
    ctx.save();
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.drawImage(this._base, 0, 0);
    ctx.restore();
    ctx.save();
    ctx.lineJoin = "round";
    ctx.lineCap = "round";
    this._drawHighlight(ctx);
    this._drawAxes(ctx);
    ctx.restore();
    if (this.options.onDraw) this.options.onDraw(this);
  };

  Preview.prototype._drawBase = function (ctx) {
    ctx.save();
    ctx.fillStyle = this.background;
    ctx.fillRect(0, 0, this.width, this.height);
    this._projectAll();
    this._drawBoundsBox(ctx);
    this._drawOrigin(ctx);

    var n = this.segments.length;
    var i;
    ctx.lineJoin = "round";
    ctx.lineCap = "round";
    // Rapids first, so cutting moves are drawn over them.
    if (this.showRapids) {
      ctx.beginPath();
      var rapidPen = newPen();
      for (i = 0; i < n; i++) if (this.buckets[i] === -1) this._tracePath(ctx, i, rapidPen);
      ctx.setLineDash([5, 4]);
      ctx.lineWidth = 1;
      ctx.strokeStyle = "rgba(255, 170, 60, 0.85)";
      ctx.stroke();
      ctx.setLineDash([]);
    }
    // One path per feed bucket keeps the number of stroke() calls small on big programs.
    var byBucket = {};
    for (i = 0; i < n; i++) {
      var k = this.buckets[i];
      if (k < 0) continue;
      (byBucket[k] || (byBucket[k] = [])).push(i);
    }
    // Lines of 1 px take the rasteriser's hairline path, several times faster than wider
    // strokes; big toolpaths use them, small ones get the easier-to-see 1.6 px.
    ctx.lineWidth = this.world.length / 3 > 20000 ? 1 : 1.6;
    for (var key in byBucket) {
      var list = byBucket[key];
      ctx.beginPath();
      var pen = newPen();
      for (var j = 0; j < list.length; j++) this._tracePath(ctx, list[j], pen);
      ctx.strokeStyle = rampColour(Number(key) / (BUCKETS - 1));
      ctx.stroke();
    }
    this._drawEndOnMoves(ctx);
    ctx.restore();
  };

  // A cutting move along the line of sight (a drill plunge in the top view) projects to a
  // point; it gets a small ring so holes stay visible.
  Preview.prototype._drawEndOnMoves = function (ctx) {
    var w = this.world;
    var scr = this.screen;
    ctx.lineWidth = 1.5;
    for (var i = 0; i < this.segments.length; i++) {
      if (this.buckets[i] < 0) continue;
      var a = this.offsets[i];
      var e = this.offsets[i + 1] - 1;
      if (e <= a) continue;
      var dx = w[3 * e] - w[3 * a];
      var dy = w[3 * e + 1] - w[3 * a + 1];
      var dz = w[3 * e + 2] - w[3 * a + 2];
      if (dx * dx + dy * dy + dz * dz < 0.25) continue;
      var sx = scr[2 * e] - scr[2 * a];
      var sy = scr[2 * e + 1] - scr[2 * a + 1];
      if (sx * sx + sy * sy > 4) continue;
      ctx.beginPath();
      ctx.arc(scr[2 * e], scr[2 * e + 1], 4, 0, 2 * Math.PI);
      ctx.strokeStyle = rampColour(this.buckets[i] / (BUCKETS - 1));
      ctx.stroke();
    }
  };

  Preview.prototype.highlightedSegments = function () {
    var out = [];
    if (this.cursorLine === null) return out;
    for (var i = 0; i < this.segments.length; i++) if (this.segments[i].line === this.cursorLine) out.push(i);
    return out;
  };

  Preview.prototype._drawHighlight = function (ctx) {
    var hl = this.highlightedSegments();
    if (!hl.length) return;
    ctx.beginPath();
    var pen = newPen();
    for (var i = 0; i < hl.length; i++) this._tracePath(ctx, hl[i], pen);
    ctx.setLineDash([]);
    ctx.lineWidth = 7;
    ctx.strokeStyle = "rgba(255, 255, 255, 0.35)";
    ctx.stroke();
    ctx.lineWidth = 3.5;
    ctx.strokeStyle = "#ff3df5";
    ctx.stroke();
    // Mark where the highlighted moves end, which is where the tool is after that block.
    var scr = this.screen;
    ctx.fillStyle = "#ffffff";
    for (i = 0; i < hl.length; i++) {
      var e = this.offsets[hl[i] + 1] - 1;
      if (e < this.offsets[hl[i]]) continue;
      ctx.beginPath();
      ctx.arc(scr[2 * e], scr[2 * e + 1], 3.5, 0, 2 * Math.PI);
      ctx.fill();
    }
  };

  Preview.prototype._drawBoundsBox = function (ctx) {
    if (!this.bounds || !this.segments.length) return;
    var lo = this.bounds.min;
    var hi = this.bounds.max;
    var self = this;
    var corner = function (i) {
      return self.project([i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]]);
    };
    var edges = [
      [0, 1], [2, 3], [4, 5], [6, 7],
      [0, 2], [1, 3], [4, 6], [5, 7],
      [0, 4], [1, 5], [2, 6], [3, 7],
    ];
    ctx.beginPath();
    for (var i = 0; i < edges.length; i++) {
      var a = corner(edges[i][0]);
      var b = corner(edges[i][1]);
      ctx.moveTo(a[0], a[1]);
      ctx.lineTo(b[0], b[1]);
    }
    ctx.setLineDash([2, 3]);
    ctx.lineWidth = 1;
    ctx.strokeStyle = "rgba(160, 160, 160, 0.35)";
    ctx.stroke();
    ctx.setLineDash([]);
  };

  // Program zero (the active work offset's origin) as a small cross-hair.
  Preview.prototype._drawOrigin = function (ctx) {
    var o = this.project([0, 0, 0]);
    ctx.beginPath();
    ctx.arc(o[0], o[1], 5, 0, 2 * Math.PI);
    ctx.moveTo(o[0] - 9, o[1]);
    ctx.lineTo(o[0] + 9, o[1]);
    ctx.moveTo(o[0], o[1] - 9);
    ctx.lineTo(o[0], o[1] + 9);
    ctx.lineWidth = 1;
    ctx.strokeStyle = "rgba(230, 230, 230, 0.6)";
    ctx.stroke();
  };

  // Axis triad in the lower-left corner, so the view orientation is always readable.
  Preview.prototype._drawAxes = function (ctx) {
    var b = this._basis();
    var ox = 34;
    var oy = this.height - 34;
    var len = 24;
    var axes = [
      { v: [1, 0, 0], c: "#ff5555", t: "X" },
      { v: [0, 1, 0], c: "#55dd55", t: "Y" },
      { v: [0, 0, 1], c: "#5599ff", t: "Z" },
    ];
    ctx.font = "11px sans-serif";
    ctx.lineWidth = 2;
    for (var i = 0; i < axes.length; i++) {
      var v = axes[i].v;
      var x1 = v[0] * b.cy - v[1] * b.sy;
      var y1 = v[0] * b.sy + v[1] * b.cy;
      var up = y1 * b.cp + v[2] * b.sp;
      var ex = ox + len * x1;
      var ey = oy - len * up;
      ctx.beginPath();
      ctx.moveTo(ox, oy);
      ctx.lineTo(ex, ey);
      ctx.strokeStyle = axes[i].c;
      ctx.stroke();
      if (Math.abs(x1) + Math.abs(up) > 0.2) {
        ctx.fillStyle = axes[i].c;
        ctx.fillText(axes[i].t, ex + (x1 >= 0 ? 3 : -10), ey + (up >= 0 ? -3 : 10));
      }
    }
  };

  /** Index of the segment drawn nearest to (x, y) in CSS pixels, or -1 if none is within reach. */
  Preview.prototype.hitTest = function (x, y) {
    var best = -1;
    var bestD = HIT_RADIUS_PX * HIT_RADIUS_PX;
    var scr = this.screen;
    // Highlight and feed moves win over rapids when both are under the pointer.
    for (var pass = 0; pass < 2 && best < 0; pass++) {
      for (var i = 0; i < this.segments.length; i++) {
        var isRapid = this.buckets[i] === -1;
        if (pass === 0 && isRapid) continue;
        if (pass === 1 && (!isRapid || !this.showRapids)) continue;
        var a = this.offsets[i];
        var e = this.offsets[i + 1];
        for (var j = a; j < e; j++) {
          var k = j + 1 < e ? j + 1 : j;
          var d = distToSegmentSq(x, y, scr[2 * j], scr[2 * j + 1], scr[2 * k], scr[2 * k + 1]);
          if (d <= bestD) {
            bestD = d;
            best = i;
          }
        }
      }
    }
    return best;
  };

  /** A point in CSS pixels on the drawn segment `index` (the midpoint of its longest piece); for tests and tooling. */
  Preview.prototype.segmentScreenPoint = function (index) {
    var a = this.offsets[index];
    var e = this.offsets[index + 1];
    if (a === undefined || e === undefined || e <= a) return null;
    var scr = this.screen;
    if (e - a === 1) return { x: scr[2 * a], y: scr[2 * a + 1] };
    var best = a;
    var bestLen = -1;
    for (var j = a; j + 1 < e; j++) {
      var dx = scr[2 * j + 2] - scr[2 * j];
      var dy = scr[2 * j + 3] - scr[2 * j + 1];
      var l = dx * dx + dy * dy;
      if (l > bestLen) {
        bestLen = l;
        best = j;
      }
    }
    return { x: (scr[2 * best] + scr[2 * best + 2]) / 2, y: (scr[2 * best + 1] + scr[2 * best + 3]) / 2 };
  };

  Preview.prototype._installInput = function () {
    var self = this;
    var canvas = this.canvas;
    var drag = null;
    var hoverPending = false;
    var lastPos = { x: 0, y: 0 };
    var pos = function (ev) {
      var r = canvas.getBoundingClientRect();
      return { x: ev.clientX - r.left, y: ev.clientY - r.top };
    };
    canvas.addEventListener("contextmenu", function (ev) {
      ev.preventDefault();
    });
    canvas.addEventListener("pointerdown", function (ev) {
      var p = pos(ev);
      // Left button orbits; right/middle button or Shift+left pans.
      var mode = ev.button === 0 && !ev.shiftKey ? "orbit" : "pan";
      drag = { x: p.x, y: p.y, sx: p.x, sy: p.y, mode: mode, moved: false, id: ev.pointerId };
      if (canvas.setPointerCapture) {
        try {
          canvas.setPointerCapture(ev.pointerId);
        } catch (e) {
          // Synthetic events may have no capturable pointer; dragging still works without capture.
        }
      }
    });
    canvas.addEventListener("pointermove", function (ev) {
      var p = pos(ev);
      if (!drag) {
        // Hit-testing walks every point, so hover runs at most once per frame.
        if (self.options.onHover && !hoverPending) {
          hoverPending = true;
          var raf = global.requestAnimationFrame || function (f) {
            return setTimeout(f, 16);
          };
          raf(function () {
            hoverPending = false;
            var i = self.hitTest(lastPos.x, lastPos.y);
            self.options.onHover(i >= 0 ? self.segments[i] : null, lastPos.x, lastPos.y);
          });
        }
        lastPos = p;
        return;
      }
      var dx = p.x - drag.x;
      var dy = p.y - drag.y;
      if (Math.abs(p.x - drag.sx) + Math.abs(p.y - drag.sy) > 3) drag.moved = true;
      if (!drag.moved) return;
      drag.x = p.x;
      drag.y = p.y;
      self._interact();
      if (drag.mode === "orbit") {
        self.yaw += dx * 0.01;
        self.pitch = Math.max(0, Math.min(Math.PI, self.pitch - dy * 0.01));
      } else {
        self.panX += dx;
        self.panY += dy;
      }
      self.requestDraw();
    });
    var end = function (ev) {
      if (!drag) return;
      var wasClick = !drag.moved && drag.mode === "orbit";
      drag = null;
      if (!wasClick) return;
      var p = pos(ev);
      var i = self.hitTest(p.x, p.y);
      if (i < 0) return;
      var line = self.segments[i].line;
      self.setCursorLine(line);
      if (self.options.onReveal) self.options.onReveal(line, self.segments[i]);
    };
    canvas.addEventListener("pointerup", end);
    canvas.addEventListener("pointercancel", function () {
      drag = null;
    });
    canvas.addEventListener("pointerleave", function () {
      if (self.options.onHover) self.options.onHover(null, 0, 0);
    });
    canvas.addEventListener(
      "wheel",
      function (ev) {
        ev.preventDefault();
        self._interact();
        var p = pos(ev);
        var f = Math.exp(-ev.deltaY * 0.0015);
        // Keep the world point under the pointer fixed while zooming.
        var cx = p.x - self.width / 2;
        var cy = p.y - self.height / 2;
        self.panX = cx - (cx - self.panX) * f;
        self.panY = cy - (cy - self.panY) * f;
        self.scale *= f;
        self.requestDraw();
      },
      { passive: false }
    );
    canvas.addEventListener("dblclick", function () {
      self.fit();
    });
  };

  Preview.rampColour = rampColour;
  Preview.formatDuration = formatDuration;
  Preview.VIEWS = VIEWS;
  global.PartscopePreview = Preview;

  // ---- Page wiring: only when loaded by preview.html (or the webview built from it). ----

  function byId(id) {
    return document.getElementById(id);
  }

  function escapeHtml(s) {
    return String(s).replace(/[&<>"]/g, function (c) {
      return { "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" }[c];
    });
  }

  function num(v, digits) {
    return typeof v === "number" && isFinite(v) ? v.toFixed(digits) : "–";
  }

  function renderStats(result) {
    var el = byId("stats");
    if (!el) return;
    var b = result.toolpath && result.toolpath.bounds;
    // A run that stopped early covers only part of the program: say so and where.
    var partial = result.complete === false;
    var rows = [
      ["Cycle time", formatDuration(result.cycle_time_s) + (partial ? " (partial)" : "")],
      ["Cutting", formatDuration(result.cutting_s)],
      ["Rapid", formatDuration(result.rapid_s)],
      ["Dwell", formatDuration(result.dwell_s)],
      ["Tool change", formatDuration(result.tool_change_s)],
      ["Distance", num(result.distance_mm, 1) + " mm"],
      ["Segments", String((result.toolpath && result.toolpath.segments || []).length)],
    ];
    // The server simplified the toolpath to fit the view (and its size cap): say how far.
    var d = result.decimation;
    if (d && d.decimated) {
      var text = d.points_out + " of " + d.points_in + " points, within " + num(d.tolerance_mm, 3) + " mm";
      if (d.truncated_at_line !== null && d.truncated_at_line !== undefined) {
        text += "; cut at line " + (d.truncated_at_line + 1) + " (size cap)";
      } else if (d.capped) {
        text += " (size cap)";
      }
      rows.push(["Toolpath", text]);
    }
    if (partial && result.stopped_at) {
      rows.splice(1, 0, ["Stopped", "at line " + (result.stopped_at.line + 1) + ": " + result.stopped_at.reason]);
    }
    if (b && b.min && b.max) {
      ["X", "Y", "Z"].forEach(function (a, i) {
        rows.push([a + " range", num(b.min[i], 3) + " … " + num(b.max[i], 3)]);
      });
    }
    el.innerHTML = rows
      .map(function (r) {
        return "<tr><th>" + escapeHtml(r[0]) + "</th><td>" + escapeHtml(r[1]) + "</td></tr>";
      })
      .join("");
  }

  function renderLegend(preview) {
    var el = byId("legend");
    if (!el) return;
    var lo = preview.feedRange[0];
    var hi = preview.feedRange[1];
    var stops = [];
    for (var i = 0; i <= 4; i++) stops.push(rampColour(i / 4));
    el.innerHTML =
      '<div class="legend-title">Feed (mm/min)</div>' +
      '<div class="legend-bar" style="background: linear-gradient(to right, ' + stops.join(", ") + ')"></div>' +
      '<div class="legend-scale"><span>' + escapeHtml(num(lo, 0)) + "</span><span>" + escapeHtml(num(hi, 0)) + "</span></div>" +
      '<div class="legend-rapid"><span class="dash"></span> rapid <span class="hl"></span> cursor line</div>';
  }

  function boot() {
    var canvas = byId("partscope-canvas");
    if (!canvas) return;
    var vscode = typeof global.acquireVsCodeApi === "function" ? global.acquireVsCodeApi() : null;
    global.partscopeOutbox = [];
    var post = function (msg) {
      if (vscode) vscode.postMessage(msg);
      global.partscopeOutbox.push(msg);
      global.dispatchEvent(new CustomEvent("partscope-post", { detail: msg }));
    };
    var tooltip = byId("tooltip");
    var preview = new Preview(canvas, {
      background: "#1e1e1e",
      onReveal: function (line) {
        post({ type: "reveal", line: line });
      },
      onHover: function (seg, x, y) {
        if (!tooltip) return;
        if (!seg) {
          tooltip.style.display = "none";
          return;
        }
        var feed = seg.kind === "rapid" ? "rapid" : (seg.feed || 0).toFixed(0) + " mm/min";
        tooltip.textContent = "line " + (seg.line + 1) + " · " + seg.kind + " · " + feed + " · T" + seg.tool;
        tooltip.style.left = x + 14 + "px";
        tooltip.style.top = y + 10 + "px";
        tooltip.style.display = "block";
      },
    });
    global.partscopePreview = preview;

    var message = byId("message");
    var showMessage = function (text) {
      if (!message) return;
      message.textContent = text || "";
      message.style.display = text ? "block" : "none";
    };

    var load = function (data, title) {
      showMessage("");
      preview.setData(data);
      renderStats(data || {});
      renderLegend(preview);
      var t = byId("title");
      if (t && title) t.textContent = title;
      if (data && data.toolpath && data.toolpath.segments && !data.toolpath.segments.length) {
        showMessage("This program has no motion.");
      }
    };

    global.addEventListener("message", function (ev) {
      var m = ev.data;
      if (!m || typeof m !== "object") return;
      if (m.type === "data") load(m.data, m.title);
      else if (m.type === "cursor") preview.setCursorLine(m.line);
      else if (m.type === "error") showMessage(m.message);
    });

    var buttons = document.querySelectorAll("[data-view]");
    for (var i = 0; i < buttons.length; i++) {
      buttons[i].addEventListener("click", function (ev) {
        preview.setView(ev.currentTarget.getAttribute("data-view"));
      });
    }
    var fitButton = byId("fit");
    if (fitButton) fitButton.addEventListener("click", function () {
      preview.fit();
    });
    var rapids = byId("show-rapids");
    if (rapids) rapids.addEventListener("change", function () {
      preview.setShowRapids(rapids.checked);
    });
    // In a narrow panel only the cycle time stays on top of the drawing.
    var layout = function () {
      document.body.classList.toggle("compact", canvas.clientWidth < 640);
    };
    layout();
    if (global.ResizeObserver) {
      new ResizeObserver(function () {
        layout();
        preview.requestDraw();
      }).observe(canvas);
    } else {
      global.addEventListener("resize", function () {
        preview.requestDraw();
      });
    }

    // A page written by `partscope run --html` carries its result in a JSON data block.
    var embedded = byId("partscope-data");
    var sample = new URLSearchParams(global.location.search).get("sample");
    if (embedded) {
      try {
        var page = JSON.parse(embedded.textContent);
        load(page.data, page.title);
      } catch (e) {
        showMessage("Could not read the embedded dry run: " + e);
      }
    } else if (!vscode && sample) {
      fetch(sample)
        .then(function (r) {
          return r.json();
        })
        .then(function (data) {
          load(data, sample);
        })
        .catch(function (e) {
          showMessage("Could not load " + sample + ": " + e);
        });
    } else {
      preview.draw();
    }
    post({ type: "ready" });
  }

  if (typeof document !== "undefined") {
    if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", boot);
    else boot();
  }
})(typeof window !== "undefined" ? window : globalThis);
