//! `check`/`run` and the language server find called files through one
//! resolver (`partscope::resolve::FsResolver`): the same candidate paths in the
//! same order, and the same file found, for a call in every dialect.

use std::path::{Path, PathBuf};

use analyzer::{Dialect, FileId};
use partscope::resolve::{FsResolver, SizeLimit};
use runtime::Resolver;

fn project(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("partscope-resolve-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join(".git")).unwrap();
    d.canonicalize().unwrap()
}

fn write(root: &Path, rel: &str, text: &str) -> PathBuf {
    let p = root.join(rel);
    std::fs::create_dir_all(p.parent().unwrap()).unwrap();
    std::fs::write(&p, text).unwrap();
    p
}

/// The two hosts' resolvers for `main` in the project `root` with the config
/// `root/partscope.toml`.
fn both(root: &Path, main: &Path, dialect: Dialect) -> (FsResolver, FsResolver) {
    let config = root.join("partscope.toml");
    let text = std::fs::read_to_string(&config).unwrap_or_default();
    let machine = analyzer::Config::from_toml(&text).unwrap().machine;
    let cli = FsResolver::for_command_line(
        main,
        dialect,
        &machine,
        Some(&config),
        SizeLimit::megabytes(128),
    );
    let lsp = FsResolver::for_workspace(
        Some(main),
        &[root.to_path_buf()],
        dialect,
        &machine,
        Some(&config),
        SizeLimit::bytes(4 << 20, "the `maxRunFileSize` setting"),
    );
    (cli, lsp)
}

#[test]
fn command_line_and_editor_resolve_alike() {
    let root = project("alike");
    write(
        &root,
        "partscope.toml",
        "[machine]\nsubroutine_path = \"lib\"\n",
    );
    // FANUC: M98 P12 finds the padded program number with a CAM extension in any case.
    let fanuc_main = write(&root, "jobs/main.nc", "O1000;\nM98 P12;\nM30;\n");
    write(&root, "lib/O0012.NC", "O0012;\nG0 X1;\nM99;\n");
    // RS274/NGC: o<drill> call finds drill.ngc in the subroutine path.
    let ngc_main = write(&root, "jobs/main.ngc", "o<drill> call\nM2\n");
    write(
        &root,
        "lib/drill.ngc",
        "o<drill> sub\nG0 Z1\no<drill> endsub\n",
    );
    // ServoWorks: M98 P<name> finds O<name>.dat beside the main program only.
    let sw_main = write(&root, "jobs/main.dat", "M98 PPocket\nM30\n");
    write(&root, "jobs/OPocket.dat", "G1 X1 F100\nM99\n");
    write(&root, "lib/OFace.dat", "G1 X1 F100\nM99\n");

    let cases = [
        (Dialect::Fanuc, &fanuc_main, "12", Some("lib/O0012.NC")),
        (Dialect::Rs274ngc, &ngc_main, "drill", Some("lib/drill.ngc")),
        (
            Dialect::Servoworks,
            &sw_main,
            "Pocket",
            Some("jobs/OPocket.dat"),
        ),
        (Dialect::Servoworks, &sw_main, "Face", None),
    ];
    for (dialect, main, name, want) in cases {
        let (cli, lsp) = both(&root, main, dialect);
        let tried = cli.candidate_paths(name, FileId(0));
        assert_eq!(
            tried,
            lsp.candidate_paths(name, FileId(0)),
            "{dialect:?} {name}"
        );
        let found = |r: &FsResolver| r.resolve(name, FileId(0)).map(|f| PathBuf::from(f.path));
        let want = want.map(|w| root.join(w));
        assert_eq!(found(&cli), want, "{dialect:?} {name}: {tried:?}");
        assert_eq!(found(&lsp), want, "{dialect:?} {name}");
        assert_eq!(
            cli.searches_like_the_control(),
            lsp.searches_like_the_control()
        );
    }

    // The candidate names and folders, in order: the caller's folder (here the
    // main program's), then the subroutine path; ServoWorks has no search path.
    let (cli, _) = both(&root, &ngc_main, Dialect::Rs274ngc);
    assert_eq!(
        cli.candidate_paths("drill", FileId(0)),
        [root.join("jobs/drill.ngc"), root.join("lib/drill.ngc")]
    );
    let (cli, _) = both(&root, &sw_main, Dialect::Servoworks);
    assert_eq!(
        cli.candidate_paths("Face", FileId(0)),
        [root.join("jobs/OFace.dat")]
    );
    let (cli, _) = both(&root, &fanuc_main, Dialect::Fanuc);
    let names: Vec<String> = cli
        .candidate_paths("12", FileId(0))
        .iter()
        .filter(|p| p.starts_with(root.join("jobs")))
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    let mut want = Vec::new();
    for base in ["O12", "O0012", "O00012", "12"] {
        for ext in ["", ".nc", ".fnc", ".txt", ".tap", ".prg"] {
            want.push(format!("{base}{ext}"));
        }
    }
    assert_eq!(names, want);
}
