;;; eglot-test.el --- Batch check of partscope.el with eglot  -*- lexical-binding: t; -*-
;; Run by editors/emacs/test.sh: opens a sample with known errors in `partscope-gcode-mode',
;; connects eglot to PARTSCOPE_BIN and requires diagnostics and a non-empty hover.

(require 'cl-lib)
;; Debian's elpa-* packages live here; -Q skips the site files that would add them.
(let ((default-directory "/usr/share/emacs/site-lisp/elpa/"))
  (when (file-directory-p default-directory)
    (normal-top-level-add-subdirs-to-load-path)))
(require 'partscope)
(require 'eglot)
(require 'flymake)

(defvar partscope-test-deadline (+ (float-time) (string-to-number (or (getenv "PARTSCOPE_TIMEOUT_S") "20"))))

(defun partscope-test-finish (ok msg)
  (princ (format "%s: %s\n" (if ok "ok" "FAIL") msg) #'external-debugging-output)
  (ignore-errors (eglot-shutdown (eglot-current-server)))
  (kill-emacs (if ok 0 1)))

(defun partscope-test-wait (pred)
  (while (and (not (funcall pred)) (< (float-time) partscope-test-deadline))
    (accept-process-output nil 0.05))
  (funcall pred))

(setq partscope-server-command (list (getenv "PARTSCOPE_BIN") "lsp"))
(find-file (getenv "PARTSCOPE_SAMPLE"))
(unless (eq major-mode 'partscope-gcode-mode)
  (partscope-test-finish nil (format "major mode is %s, not partscope-gcode-mode" major-mode)))
(condition-case err
    (apply #'eglot (eglot--guess-contact))
  (error (partscope-test-finish nil (format "eglot did not start: %S" err))))
(unless (partscope-test-wait (lambda () (and (fboundp 'eglot-current-server) (eglot-current-server))))
  (partscope-test-finish nil "no eglot server for the buffer"))
(unless (partscope-test-wait (lambda ()
                               (flymake-start)
                               (flymake-diagnostics)))
  (partscope-test-finish nil "no diagnostics arrived for a sample with known errors"))
;; M-x partscope-toolpath writes the page with `partscope run --html' (here handed to a
;; function instead of the browser).
(let (written)
  (with-current-buffer (get-file-buffer (getenv "PARTSCOPE_SAMPLE"))
    (partscope-toolpath (lambda (page) (setq written page))))
  (unless (partscope-test-wait (lambda () written))
    (partscope-test-finish nil "partscope-toolpath wrote no page"))
  (let ((page (with-temp-buffer (insert-file-contents written) (buffer-string))))
    ;; The sample's one drawn move: the rapid of line 3 to X0 Y0 Z5.
    (unless (and (string-match-p "id=\"partscope-data\"" page)
                 (string-match-p (regexp-quote "\"points\":[[0.0,0.0,0.0],[0.0,0.0,5.0]]") page))
      (partscope-test-finish nil (format "the page lacks the sample's dry run: %s" (substring page 0 200))))))
(goto-char (point-min))
(search-forward "G21")
(backward-char 2)
(let* ((hover (jsonrpc-request (eglot-current-server) :textDocument/hover
                               (eglot--TextDocumentPositionParams)))
       (contents (plist-get hover :contents))
       (text (cond ((stringp contents) contents)
                   ((and (listp contents) (plist-get contents :value)))
                   ((vectorp contents) (mapconcat (lambda (c) (if (stringp c) c (or (plist-get c :value) "")))
                                                  contents "\n"))
                   (t ""))))
  ;; FANUC `.fnc' and ServoWorks `.sw' files open in the mode too, and `comment-region'
  ;; writes ( ), never `;' (which ends a FANUC block).
  (dolist (name '("O1000.fnc" "part.sw"))
    (with-current-buffer (find-file-noselect (expand-file-name name (file-name-directory (getenv "PARTSCOPE_SAMPLE"))))
      (unless (eq major-mode 'partscope-gcode-mode)
        (partscope-test-finish nil (format "%s opens in %s, not partscope-gcode-mode" name major-mode)))
      (insert "G00 X1.;")
      (comment-region (point-min) (point-max))
      (unless (string-match-p "\\`( *G00 X1\\.; *)\\'" (buffer-string))
        (partscope-test-finish nil (format "comment-region in %s wrote %S" name (buffer-string))))
      (set-buffer-modified-p nil)))
  (if (string-blank-p (or text ""))
      (partscope-test-finish nil (format "hover returned no content: %S" hover))
    (partscope-test-finish t (format "%d diagnostic(s), first: %s; hover: %s"
                                     (length (flymake-diagnostics))
                                     (flymake-diagnostic-text (car (flymake-diagnostics)))
                                     (truncate-string-to-width (replace-regexp-in-string "\\s-+" " " text) 80)))))
;;; eglot-test.el ends here
