// Turns media/preview.html (which also works as a plain page) into webview HTML: a
// Content-Security-Policy and webview URIs for its stylesheet and script. Kept free of the
// `vscode` module so the browser test can load exactly what the webview gets.

export interface WebviewResources {
  /** `webview.cspSource`: the origin webview resources are served from. */
  cspSource: string;
  /** Webview URI of media/preview.css. */
  cssUri: string;
  /** Webview URI of media/preview.js. */
  scriptUri: string;
}

export const CSP_MARKER = "<!-- partscope:csp -->";

export function webviewHtml(template: string, r: WebviewResources): string {
  if (!template.includes(CSP_MARKER)) throw new Error("preview.html lacks the CSP marker");
  // Inline style attributes are needed for the legend's gradient; no inline script is allowed.
  const csp =
    `<meta http-equiv="Content-Security-Policy" content="default-src 'none'; ` +
    `img-src ${r.cspSource} data:; style-src ${r.cspSource} 'unsafe-inline'; ` +
    `script-src ${r.cspSource};">`;
  return template
    .replace(CSP_MARKER, csp)
    .replace('href="preview.css"', `href="${r.cssUri}"`)
    .replace('src="preview.js"', `src="${r.scriptUri}"`);
}
