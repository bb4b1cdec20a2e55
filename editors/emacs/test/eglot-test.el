;;; eglot-test.el --- Batch check of partscope.el with eglot  -*- lexical-binding: t; -*-
;; Run by editors/emacs/test.sh: opens a sample with known errors in `partscope-gcode-mode',
;; connects eglot to PARTSCOPE_BIN and requires diagnostics and a non-empty hover; then the
;; cycle-time lens's command, inlay block times, loop values on hover, formatting and rename on
;; editors/test/loop.ngc, checked against `partscope run'.

(require 'cl-lib)
;; Debian's elpa-* packages live here; -Q skips the site files that would add them.
(let ((default-directory "/usr/share/emacs/site-lisp/elpa/"))
  (when (file-directory-p default-directory)
    (normal-top-level-add-subdirs-to-load-path)))
(require 'partscope)
(require 'eglot)
(require 'flymake)

(defvar partscope-test-deadline (+ (float-time) (string-to-number (or (getenv "PARTSCOPE_TIMEOUT_S") "20"))))

(defvar partscope-test-summary nil "What the first checks found, printed at the end.")

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
  (when (string-blank-p (or text ""))
    (partscope-test-finish nil (format "hover returned no content: %S" hover)))
  (setq partscope-test-summary
        (format "%d diagnostic(s), first: %s; hover: %s"
                (length (flymake-diagnostics))
                (flymake-diagnostic-text (car (flymake-diagnostics)))
                (truncate-string-to-width (replace-regexp-in-string "\\s-+" " " text) 80))))

;; The dry-run features on editors/test/loop.ngc, against the CLI's figures for the same file.
(defun partscope-test-cli (file &rest args)
  "The JSON `partscope run FILE ARGS' prints, as a plist."
  (with-temp-buffer
    (let ((rc (apply #'call-process (getenv "PARTSCOPE_BIN") nil '(t nil) nil "run" file args)))
      (unless (eql rc 0)
        (partscope-test-finish nil (format "partscope run %s exited %s: %s" file rc (buffer-string))))
      (json-parse-string (buffer-string) :object-type 'plist :array-type 'list))))

(defun partscope-test-goto (needle)
  "Put point on NEEDLE's first character."
  (goto-char (point-min))
  (search-forward needle)
  (goto-char (match-beginning 0)))

(defvar partscope-test-loop (getenv "PARTSCOPE_LOOP"))
(defvar partscope-test-cli-run (partscope-test-cli partscope-test-loop "--format" "json" "--what-if" "off"))
(find-file partscope-test-loop)
(unless (partscope-test-wait (lambda () (bound-and-true-p eglot--managed-mode)))
  (partscope-test-finish nil "eglot does not manage loop.ngc"))
(let* ((cycle (plist-get partscope-test-cli-run :cycle_time_s))
       (want-first (format "loop.ngc: cycle time %s (%.3f s)" (partscope-format-duration cycle) cycle))
       (server (eglot-current-server))
       (doc (eglot--TextDocumentIdentifier)))
  ;; (a) The lens's command, as a client with code lenses runs it on a click: the server
  ;; answers with the breakdown (and shows it as a message).
  (let* ((lenses (jsonrpc-request server :textDocument/codeLens (list :textDocument doc)))
         (cmd (plist-get (elt lenses 0) :command))
         (title (plist-get cmd :title))
         (r (eglot-execute-command server (plist-get cmd :command) (plist-get cmd :arguments))))
    (unless (string-prefix-p (format "Cycle time %s " (partscope-format-duration cycle)) title)
      (partscope-test-finish nil (format "the lens is %S; the CLI's cycle time is %s s" title cycle)))
    (unless (equal (car (split-string (plist-get r :text) "\n")) want-first)
      (partscope-test-finish nil (format "the lens's command gave %S, expected it to start with %S"
                                         (plist-get r :text) want-first))))
  ;; M-x partscope-breakdown: the same breakdown in a help buffer.
  (let ((r (partscope-breakdown))
        (shown (with-current-buffer "*partscope breakdown*" (buffer-string))))
    (unless (and (equal (car (split-string shown "\n")) want-first)
                 (string-match-p "^where the time goes$" shown)
                 (equal (plist-get r :cycle_time_s) cycle))
      (partscope-test-finish nil (format "partscope-breakdown showed %S" shown))))
  ;; (b) Inlay block times, each the CLI's time of that line's block.
  (let* ((hints (jsonrpc-request server :textDocument/inlayHint
                                 (list :textDocument doc
                                       :range (list :start (list :line 0 :character 0)
                                                    :end (list :line (count-lines (point-min) (point-max))
                                                               :character 0)))))
         (got (mapconcat (lambda (h)
                           (let ((label (plist-get h :label)))
                             (format "%d:%s" (1+ (plist-get (plist-get h :position) :line))
                                     (if (stringp label) label (plist-get (elt label 0) :value)))))
                         hints " "))
         (want (mapconcat (lambda (b) (format "%d:%.3f s" (plist-get b :line) (plist-get b :time_s)))
                          (plist-get partscope-test-cli-run :blocks) " ")))
    (unless (and (equal got want) (equal want "3:0.142 s 4:1.200 s 8:2.997 s 10:0.500 s 11:0.220 s"))
      (partscope-test-finish nil (format "inlay hints %s; the CLI's blocks %s" got want))))
  ;; (c) Hover on #1 in the loop's move: each of the three executions' value.
  (partscope-test-goto "X[#1")
  (forward-char 2)
  (let* ((h (jsonrpc-request server :textDocument/hover (eglot--TextDocumentPositionParams)))
         (md (plist-get (plist-get h :contents) :value)))
    (unless (and md (string-match-p (regexp-quote "Value in the dry run: `3` (last of 3 executions)  \nEach execution: `1`, `2`, `3`") md))
      (partscope-test-finish nil (format "hover on #1 in the loop lacks its values: %S" md))))
  ;; (e) M-x eglot-format-buffer keeps the dry run: the formatted buffer, written beside,
  ;; runs the same as the file.
  (eglot-format-buffer)
  (let ((want (concat "(partscope: dialect=rs274ngc)\nG21 G90 G17 G94\nG0 X0 Y0 Z5\nG1 Z-1 F300\n"
                      "#1 = 0\no100 while [#1 LT 3]\n  #1 = [#1 + 1]\n  G1 X[#1 * 10] F600\n"
                      "o100 endwhile\nG4 P0.5\nG0 Z5\nM2\n"))
        (formatted (expand-file-name "loop_formatted.ngc" (file-name-directory partscope-test-loop))))
    (unless (equal (buffer-string) want)
      (partscope-test-finish nil (format "formatting gave %S" (buffer-string))))
    (write-region (point-min) (point-max) formatted nil 'quiet)
    (let ((after (partscope-test-cli formatted "--format" "json" "--what-if" "off"))
          (motions (lambda (f) (length (plist-get (partscope-test-cli f "--emit" "toolpath") :segments)))))
      (unless (and (equal (plist-get after :cycle_time_s) cycle)
                   (= (funcall motions partscope-test-loop) 6)
                   (= (funcall motions formatted) 6))
        (partscope-test-finish nil (format "formatting changed the dry run: %s s -> %s s, motions %d -> %d"
                                           cycle (plist-get after :cycle_time_s)
                                           (funcall motions partscope-test-loop)
                                           (funcall motions formatted)))))
    (set-buffer-modified-p nil)))

;; (d) Rename across two files: the call here, the subroutine file's sub/endsub.
(let ((dir (file-name-directory partscope-test-loop)))
  (with-temp-file (expand-file-name "drill.ngc" dir) (insert "o<drill> sub\nG0 X#1\no<drill> endsub\n"))
  (with-temp-file (expand-file-name "calls.ngc" dir) (insert "o<drill> call [5]\nM2\n"))
  (let ((lib (find-file-noselect (expand-file-name "drill.ngc" dir))))
    (find-file (expand-file-name "calls.ngc" dir))
    (unless (partscope-test-wait (lambda () (and (bound-and-true-p eglot--managed-mode)
                                                 (with-current-buffer lib (bound-and-true-p eglot--managed-mode)))))
      (partscope-test-finish nil "eglot does not manage calls.ngc and drill.ngc"))
    (partscope-test-goto "drill")
    (eglot-rename "peck")
    (unless (equal (buffer-string) "o<peck> call [5]\nM2\n")
      (partscope-test-finish nil (format "rename left calls.ngc as %S" (buffer-string))))
    (unless (equal (with-current-buffer lib (buffer-string)) "o<peck> sub\nG0 X#1\no<peck> endsub\n")
      (partscope-test-finish nil (format "rename did not reach drill.ngc: %S" (with-current-buffer lib (buffer-string)))))
    (with-current-buffer lib (set-buffer-modified-p nil))
    (set-buffer-modified-p nil)))

(partscope-test-finish t partscope-test-summary)
;;; eglot-test.el ends here
