;;; partscope.el --- G-code major mode and Partscope language server setup  -*- lexical-binding: t; -*-

;; Version: 0.1.0
;; Package-Requires: ((emacs "27.1"))
;; Keywords: languages, cnc, gcode
;; SPDX-License-Identifier: MIT OR Apache-2.0

;;; Commentary:

;; A small major mode for CNC part programs (ServoWorks, LinuxCNC RS274/NGC, FANUC) that
;; registers the Partscope language server (`partscope lsp') with both eglot and lsp-mode.
;;
;;   (add-to-list 'load-path "/path/to/partscope/editors/emacs")
;;   (require 'partscope)
;;   (add-hook 'partscope-gcode-mode-hook #'eglot-ensure)   ; or #'lsp-deferred
;;
;; M-x partscope-dry-run shows the cycle time; M-x partscope-breakdown shows where it goes
;; (what the cycle-time code lens shows in editors with lenses); M-x partscope-toolpath opens the toolpath
;; in the browser (`partscope run FILE --html PAGE'); M-x partscope-explain-rule runs
;; `partscope rule CODE'.

;;; Code:

(require 'cl-lib)
(require 'subr-x)
(require 'eieio)

(defgroup partscope nil
  "CNC part programs checked by the Partscope language server."
  :group 'languages
  :prefix "partscope-")

(defcustom partscope-server-command '("partscope" "lsp")
  "Command that starts the Partscope language server."
  :type '(repeat string))

(defcustom partscope-dialect nil
  "Dialect of the part programs, or nil to let Partscope decide per file."
  :type '(choice (const :tag "Decide per file" nil)
                 (const "servoworks") (const "rs274ngc") (const "fanuc")))

(defcustom partscope-machine nil
  "Machine profile (TOML, or a LinuxCNC .ini) for limits and cycle time, or nil."
  :type '(choice (const nil) file))

(defcustom partscope-select nil
  "Rule codes or prefixes to enable (nil: the defaults)."
  :type '(repeat string))

(defcustom partscope-ignore nil
  "Rule codes or prefixes to silence."
  :type '(repeat string))

(defcustom partscope-open-command nil
  "Command that opens the page `partscope-toolpath' writes; its file is appended.
nil: the system's opener, xdg-open (open on macOS, start on Windows)."
  :type '(choice (const :tag "System opener" nil) (repeat string)))

(defconst partscope-file-extensions
  '("nc" "ngc" "tap" "cnc" "gcode" "eia" "dat" "min" "mpf" "fnc" "sw")
  "File extensions opened in `partscope-gcode-mode'.")

(defun partscope--init-options ()
  "The initializationOptions object for the server, as a plist.
nil encodes as JSON null and vectors as arrays in both eglot and lsp-mode."
  (list :dialect partscope-dialect
        :machine (and partscope-machine (expand-file-name partscope-machine))
        :select (vconcat partscope-select)
        :ignore (vconcat partscope-ignore)))

;;;; Major mode

(defvar partscope-gcode-mode-syntax-table
  (let ((st (make-syntax-table)))
    ;; ( ... ) comments in every dialect; ; to end of line in RS274/NGC.
    (modify-syntax-entry ?\( "< b" st)
    (modify-syntax-entry ?\) "> b" st)
    (modify-syntax-entry ?\; "<" st)
    (modify-syntax-entry ?\n ">" st)
    (modify-syntax-entry ?\[ "(]" st)
    (modify-syntax-entry ?\] ")[" st)
    (modify-syntax-entry ?# "'" st)
    (modify-syntax-entry ?_ "_" st)
    (modify-syntax-entry ?. "_" st)
    st)
  "Syntax table for `partscope-gcode-mode'.")

(defconst partscope--font-lock-keywords
  (let ((case-fold-search t))
    `(;; ServoWorks: % at the start of a line comments out the line.
      ("^%.+$" . font-lock-comment-face)
      ("^\\s-*\\(/[0-9]?\\)" 1 font-lock-preprocessor-face)
      ("\\_<[nN][0-9]+" . font-lock-doc-face)
      ;; RS274/NGC o-words with their keyword.
      (,(concat "\\_<\\([oO]\\s-*\\(?:<[^>]*>\\|[0-9]+\\)\\)\\s-*"
                (regexp-opt '("sub" "endsub" "call" "return" "if" "elseif" "else" "endif"
                              "while" "endwhile" "do" "repeat" "endrepeat" "break" "continue")
                            'words))
       (1 font-lock-function-name-face) (2 font-lock-keyword-face))
      ("\\_<[oO]\\s-*\\(?:<[^>]*>\\|[0-9]+\\|[A-Za-z_][A-Za-z0-9_]*\\)" . font-lock-function-name-face)
      ;; FANUC Custom Macro B.
      ("\\(?:\\_<\\|[0-9\\]]\\)\\(IF\\|THEN\\|WHILE\\|GOTO\\|DO[0-9]+\\|END[0-9]+\\)" 1 font-lock-keyword-face)
      (,(concat (regexp-opt '("ATAN" "ASIN" "ACOS" "SQRT" "ROUND" "EXISTS" "SIN" "COS" "TAN"
                              "ABS" "BIN" "BCD" "FIX" "FUP" "LN" "EXP" "POW" "ADP"))
                "\\s-*\\[")
       . font-lock-builtin-face)
      ("[gG]\\s-*[0-9]+\\(?:\\.[0-9]+\\)?" . font-lock-keyword-face)
      ("[mM]\\s-*[0-9]+" . font-lock-preprocessor-face)
      ("[tT]\\s-*[0-9]+" . font-lock-type-face)
      ("#\\(?:<[^>]*>\\|[0-9]+\\|_[A-Za-z0-9_]+\\)" . font-lock-variable-name-face)
      ("[xXyYzZaAbBcCuUvVwW]\\(?=\\s-*[-+.0-9#[]\\)" . font-lock-constant-face)
      ("[iIjJkKrR]\\(?=\\s-*[-+.0-9#[]\\)" . font-lock-constant-face)))
  "Highlighting for `partscope-gcode-mode'.
Semantic tokens from the server refine it.")

;;;###autoload
(define-derived-mode partscope-gcode-mode prog-mode "G-code"
  "Major mode for CNC part programs, backed by the Partscope language server."
  :syntax-table partscope-gcode-mode-syntax-table
  (setq-local comment-start "(")
  (setq-local comment-end ")")
  (setq-local comment-start-skip "\\(?:(\\|;\\)\\s-*")
  (setq-local font-lock-defaults '(partscope--font-lock-keywords nil t)))

;;;###autoload
(add-to-list 'auto-mode-alist
             (cons (concat "\\." (regexp-opt partscope-file-extensions t) "\\'") 'partscope-gcode-mode))
;;;###autoload
(add-to-list 'auto-mode-alist
             (cons (concat "\\." (regexp-opt (mapcar #'upcase partscope-file-extensions) t) "\\'")
                   'partscope-gcode-mode))

;;;; eglot

(declare-function eglot-current-server "eglot")
(declare-function eglot--current-server-or-lose "eglot")
(declare-function jsonrpc-request "jsonrpc")
(defvar eglot-server-programs)
;; Generated by the `defclass' below, which runs only once eglot is loaded.
(declare-function partscope-eglot-server--eieio-childp "partscope")

(with-eval-after-load 'eglot
  ;; A server class of our own, so initializationOptions work with every eglot version
  ;; (the `:initializationOptions' contact keyword is newer than some distributions' eglot).
  (defclass partscope-eglot-server (eglot-lsp-server) ()
    :documentation "Partscope language server.")
  (cl-defmethod eglot-initialization-options ((_server partscope-eglot-server))
    (partscope--init-options))
  (add-to-list 'eglot-server-programs
               `(partscope-gcode-mode . (partscope-eglot-server . ,(lambda (&rest _) partscope-server-command)))))

;;;; lsp-mode

(declare-function lsp-register-client "lsp-mode")
(declare-function make-lsp-client "lsp-mode")
(declare-function lsp-stdio-connection "lsp-mode")
(declare-function lsp-activate-on "lsp-mode")
(declare-function lsp-register-custom-settings "lsp-mode")
(declare-function lsp-request "lsp-mode")
(declare-function lsp--text-document-identifier "lsp-mode")
(declare-function lsp-workspaces "lsp-mode")
(defvar lsp-language-id-configuration)

(with-eval-after-load 'lsp-mode
  (add-to-list 'lsp-language-id-configuration '(partscope-gcode-mode . "gcode"))
  ;; Answers workspace/configuration for the `partscope' section.
  (lsp-register-custom-settings
   '(("partscope.dialect" partscope-dialect)
     ("partscope.machine" partscope-machine)
     ("partscope.select" partscope-select)
     ("partscope.ignore" partscope-ignore)))
  (lsp-register-client
   (make-lsp-client
    :new-connection (lsp-stdio-connection (lambda () partscope-server-command))
    :activation-fn (lsp-activate-on "gcode")
    :initialization-options #'partscope--init-options
    :server-id 'partscope)))

;;;; Commands

(defun partscope--request (method params)
  "Send METHOD with PARAMS to the Partscope server of this buffer.
Uses eglot or lsp-mode, whichever manages the buffer."
  (cond
   ((and (bound-and-true-p eglot--managed-mode) (fboundp 'jsonrpc-request))
    (jsonrpc-request (if (fboundp 'eglot-current-server)
                         (or (eglot-current-server) (user-error "No eglot server here"))
                       (eglot--current-server-or-lose))
                     (intern (concat ":" method)) params))
   ((and (bound-and-true-p lsp-mode) (fboundp 'lsp-request))
    (lsp-request method params))
   (t (user-error "Partscope: start eglot or lsp-mode in this buffer first"))))

(defun partscope-format-duration (seconds)
  "SECONDS as m:ss.s below an hour and h:mm:ss above."
  (if (not (numberp seconds))
      "-"
    (let ((a (abs seconds)))
      (concat
       (if (< seconds 0) "-" "")
       (if (< a 3599.95)
           (let* ((tenths (round (* a 10)))
                  (m (/ tenths 600)))
             (format "%d:%04.1f" m (/ (- tenths (* m 600)) 10.0)))
         (let ((whole (round a)))
           (format "%d:%02d:%02d" (/ whole 3600) (/ (% whole 3600) 60) (% whole 60))))))))

(declare-function eglot--TextDocumentIdentifier "eglot")

(defun partscope--text-document ()
  "The LSP TextDocumentIdentifier of this buffer, as its client spells the URI."
  (cond
   ((and (bound-and-true-p eglot--managed-mode) (fboundp 'eglot--TextDocumentIdentifier))
    (eglot--TextDocumentIdentifier))
   ((and (bound-and-true-p lsp-mode) (fboundp 'lsp--text-document-identifier))
    (lsp--text-document-identifier))
   (t (user-error "Partscope: start eglot or lsp-mode in this buffer first"))))

(defun partscope-dry-run ()
  "Show the cycle time of the current buffer as computed by the Partscope server."
  (interactive)
  (let* ((r (partscope--request "partscope/dryRun" (list :textDocument (partscope--text-document))))
         (get (lambda (k) (plist-get r k)))
         (segs (plist-get (plist-get r :toolpath) :segments))
         (name (buffer-name)))
    (with-help-window "*partscope dry run*"
      (princ (format "Dry run of %s\n\n" name))
      (dolist (row `(("cycle time" . ,(partscope-format-duration (funcall get :cycle_time_s)))
                     ("  cutting" . ,(partscope-format-duration (funcall get :cutting_s)))
                     ("  rapid" . ,(partscope-format-duration (funcall get :rapid_s)))
                     ("  dwell" . ,(partscope-format-duration (funcall get :dwell_s)))
                     ("  tool change" . ,(partscope-format-duration (funcall get :tool_change_s)))
                     ("distance" . ,(format "%.1f mm" (or (funcall get :distance_mm) 0)))
                     ("segments" . ,(format "%d" (length segs)))))
        (princ (format "%-14s%14s\n" (car row) (cdr row)))))))

(defconst partscope-breakdown-command "partscope.showBreakdown"
  "The server command behind the cycle-time code lens.")

(declare-function eglot-execute-command "eglot")

(defun partscope--execute-command (command arguments)
  "Run the server's COMMAND with ARGUMENTS (a vector) and return its result.
Uses eglot or lsp-mode, whichever manages the buffer."
  (cond
   ((and (bound-and-true-p eglot--managed-mode) (fboundp 'eglot-execute-command))
    (eglot-execute-command (if (fboundp 'eglot-current-server)
                               (or (eglot-current-server) (user-error "No eglot server here"))
                             (eglot--current-server-or-lose))
                           command arguments))
   ((and (bound-and-true-p lsp-mode) (fboundp 'lsp-request))
    (lsp-request "workspace/executeCommand" (list :command command :arguments arguments)))
   (t (user-error "Partscope: start eglot or lsp-mode in this buffer first"))))

(defun partscope-breakdown ()
  "Show where the cycle time of the current buffer goes.
This is what the cycle-time code lens shows in editors with code
lenses (eglot has none): the server's `partscope.showBreakdown'
command, its text shown in the buffer *partscope breakdown*.
Returns the command's result."
  (interactive)
  (let* ((uri (plist-get (partscope--text-document) :uri))
         ;; :show false: the text is shown here, not also as a server message.
         (r (partscope--execute-command partscope-breakdown-command
                                        (vector uri (list :show :json-false)))))
    (with-help-window "*partscope breakdown*"
      ;; eglot gives plists; lsp-mode gives hash tables unless `lsp-use-plists' is set.
      (princ (or (if (hash-table-p r) (gethash "text" r) (plist-get r :text)) "")))
    r))

(defun partscope--opener ()
  "The command that opens a file in the browser, as a list."
  (or partscope-open-command
      (pcase system-type
        ('darwin '("open"))
        ('windows-nt '("cmd" "/c" "start" ""))
        (_ '("xdg-open")))))

(defun partscope-toolpath (&optional on-written)
  "Open the toolpath of the current file in the browser.
Runs `partscope run FILE --html PAGE' with PAGE a temporary file,
then opens PAGE with `partscope-open-command'.  ON-WRITTEN, when
given, is called with PAGE instead.  The page shows the file as saved."
  (interactive)
  (let ((file (or buffer-file-name (user-error "Partscope: this buffer has no file; save it first")))
        (page (make-temp-file "partscope-" nil ".html"))
        (errors (generate-new-buffer " *partscope toolpath*")))
    (when (buffer-modified-p)
      (message "Partscope: the buffer has unsaved changes; the page shows the file as saved"))
    (make-process
     :name "partscope-toolpath"
     :command (list (car partscope-server-command) "run" file "--html" page)
     :buffer nil
     :stderr errors
     :noquery t
     :sentinel
     (lambda (proc _event)
       (unless (process-live-p proc)
         ;; `run' exits 1 for a program with errors or a partial run, and writes the page then too.
         (if (and (<= (process-exit-status proc) 1)
                  (> (or (file-attribute-size (file-attributes page)) 0) 0))
             (if on-written
                 (funcall on-written page)
               (let ((cmd (partscope--opener)))
                 (apply #'call-process (car cmd) nil 0 nil (append (cdr cmd) (list page)))))
           (message "Partscope: `partscope run --html' failed (%d): %s"
                    (process-exit-status proc)
                    (string-trim (with-current-buffer errors (buffer-string)))))
         (run-at-time 0 nil (lambda () (when (buffer-live-p errors) (kill-buffer errors)))))))))

(defun partscope-explain-rule (code)
  "Show the documentation of rule CODE (`partscope rule CODE')."
  (interactive (list (read-string "Rule code: " (partscope--code-at-point))))
  (with-help-window (format "*partscope rule %s*" code)
    (princ (with-output-to-string
             (with-current-buffer standard-output
               (call-process (car partscope-server-command) nil t nil "rule" code))))))

(defun partscope--code-at-point ()
  "The code of a diagnostic at point, if flymake knows one."
  (when (fboundp 'flymake-diagnostics)
    (cl-some (lambda (d)
               (let ((text (flymake-diagnostic-text d)))
                 (and (string-match "\\_<\\([A-Z]+[0-9]+\\)\\_>" text) (match-string 1 text))))
             (flymake-diagnostics (point)))))

(declare-function flymake-diagnostics "flymake")
(declare-function flymake-diagnostic-text "flymake")

(provide 'partscope)
;;; partscope.el ends here
