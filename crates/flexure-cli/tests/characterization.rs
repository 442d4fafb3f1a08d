//! Characterization of every subcommand's answer, kept before the Seam
//! issue moves code: each call's exit status and `--json` output on the
//! examples and on a set of single-joint calls, against
//! `tests/data/characterization.json`. A regression guard, not a check of
//! correctness (the other tests check the numbers against closed forms and
//! the exact references): it says that a refactoring changed no answer.
//!
//! Numbers must agree to 1e-12 relative (1e-14 absolute, for residuals at
//! rounding's level); integers (step counts, orders) and everything else
//! exactly. `scripts/characterize.sh` adds the answers of calls appended to
//! [`calls`] and keeps every answer the file holds byte for byte
//! (`FLEXURE_BLESS=new`); `scripts/characterize.sh --all` rewrites them all,
//! after a change that is meant to change answers (say which in the commit;
//! `FLEXURE_BLESS=all`).
//!
//! Keys renamed since the file was written (`CHANGELOG.md`, *Changed*) are
//! mapped in the golden answers before comparing, by [`RENAMES`], [`CALLS`]
//! and [`TEXTS`], so every number it holds is still checked; keys added
//! since (*Added*) are left out of today's answers by [`ADDED`].

use crate::cli::run;
use serde_json::{Value, json};

const GOLDEN: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/characterization.json");

/// Renamed JSON keys, as `CHANGELOG.md` lists them: (the calls they apply
/// to, by the start of their text; old key; new key).
const RENAMES: &[(&str, &str, &str)] =
    &[("deflect", "limit_load_fraction", "limit_fraction"), ("tendon", "force", "tension")];

/// Renamed options, as `CHANGELOG.md` lists them: the golden call's text
/// with the old option, and with the new.
const CALLS: &[(&str, &str)] = &[("tendon --force ", "tendon --tension ")];

/// Keys added since the file was written (`CHANGELOG.md`, *Added*): (the
/// calls, by the start of their text; a key inside an `error_estimate`).
/// They are left out of today's answer where the golden one lacks them;
/// every key the golden answer has is still compared.
const ADDED: &[(&str, &str)] =
    &[("solve", "reference"), ("solve", "reference_order"), ("solve", "reference_quadrature")];

/// Keys added since the file was written at the top of an answer
/// (`CHANGELOG.md`, *Changed*: one solve report for both dimensions, and the
/// same keys in every mechanism answer; one export report for both
/// dimensions): (the calls, by the start of their
/// text; the key). Left out of today's answer where the golden one lacks them.
const ADDED_TOP: &[(&str, &str)] = &[
    ("solve", "dimension"),
    ("solve", "load"),
    ("solve", "multipliers"),
    ("solve", "residual"),
    ("solve", "load_steps"),
    ("solve", "iterations"),
    ("buckle", "dimension"),
    ("modes", "dimension"),
    ("modes", "findings"),
    ("modes", "quasi_static"),
    ("modes", "note"),
    ("simulate", "dimension"),
    ("simulate", "error_estimate"),
    ("simulate", "flagged"),
    ("export", "dimension"),
];

/// `now` without the [`ADDED_TOP`] keys that `golden` lacks.
fn without_added_top(call: &str, now: &Value, golden: &Value) -> Value {
    match (now, golden) {
        (Value::Object(n), Value::Object(g)) => Value::Object(
            n.iter()
                .filter(|(k, _)| g.contains_key(*k) || !ADDED_TOP.iter().any(|(c, a)| call.starts_with(c) && a == k))
                .map(|(k, v)| (k.clone(), v.clone()))
                .collect(),
        ),
        _ => now.clone(),
    }
}

/// A spatial solve's golden answer in today's shape, the planar one's
/// (`CHANGELOG.md`, *Changed*): `bodies` a map by name, the ground
/// included, of x, y, z, roll, pitch, yaw and rotation; `coordinates` by
/// joint; per flexure joint `error_estimate`, `load` and `stress` (its
/// von Mises peak as `max`, the section's `point`, beside its parts);
/// `q` and the list of flexures gone. Every number it held is compared.
fn reshaped(answer: &Value) -> Value {
    let Some(old) = answer.as_object().filter(|a| a.contains_key("flexures") && a.contains_key("joints")) else {
        return answer.clone();
    };
    let mut new = old.clone();
    for key in ["q", "joints", "flexures", "bodies"] {
        new.remove(key);
    }
    let identity = json!([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    let mut bodies = serde_json::Map::new();
    let ground = json!({ "x": 0.0, "y": 0.0, "z": 0.0, "roll": 0.0, "pitch": 0.0, "yaw": 0.0, "rotation": identity });
    bodies.insert("ground".into(), ground);
    for b in old["bodies"].as_array().into_iter().flatten() {
        let (p, r) = (&b["position"], &b["rpy"]);
        let pose = json!({ "x": p[0], "y": p[1], "z": p[2], "roll": r[0], "pitch": r[1], "yaw": r[2], "rotation": b["rotation"] });
        bodies.insert(b["name"].as_str().unwrap_or_default().into(), pose);
    }
    new.insert("bodies".into(), Value::Object(bodies));
    let by_name = |list: &Value, f: &dyn Fn(&Value) -> Option<Value>| -> Value {
        Value::Object(
            list.as_array()
                .into_iter()
                .flatten()
                .filter_map(|x| Some((x["name"].as_str()?.to_string(), f(x)?)))
                .collect(),
        )
    };
    new.insert("coordinates".into(), by_name(&old["joints"], &|j| Some(j["coordinates"].clone())));
    new.insert("error_estimate".into(), by_name(&old["flexures"], &|f| Some(f["error_estimate"].clone())));
    new.insert("load".into(), by_name(&old["flexures"], &|f| Some(f["load"].clone())));
    let stress = by_name(&old["flexures"], &|f| {
        let (s, at) = (&f["stress"]["stress"], &f["stress"]["at"]);
        (!s.is_null()).then(|| {
            json!({ "max": s["von_mises"], "at": at, "point": s["at"], "bending_y": s["bending_y"],
                    "bending_z": s["bending_z"], "shear": s["shear"] })
        })
    });
    if stress.as_object().is_some_and(|s| !s.is_empty()) {
        new.insert("stress".into(), stress);
    }
    Value::Object(new)
}

/// Keys added at any depth of an answer since the file was written
/// (`CHANGELOG.md`, *Added*), as [`ADDED`]: (the calls, by the start of
/// their text; the key).
const ADDED_ANYWHERE: &[(&str, &str)] = &[
    ("deflect", "stability_test"),
    ("deflect --spatial", "roll"),
    ("deflect --spatial", "pitch"),
    ("deflect --spatial", "yaw"),
    ("kinematics --spatial", "roll"),
    ("kinematics --spatial", "pitch"),
    ("kinematics --spatial", "yaw"),
];

/// A single spatial flexure's golden `pose` `{position, rotation}` in
/// today's shape, a mechanism body's (`CHANGELOG.md`, *Changed*): `x`,
/// `y`, `z` and `rotation`, every number compared; roll, pitch and yaw
/// are [`ADDED_ANYWHERE`].
fn poses_reshaped(answer: &Value) -> Value {
    match answer {
        Value::Object(map) => Value::Object(
            map.iter()
                .map(|(k, v)| match (k.as_str(), v.get("position")) {
                    ("pose", Some(p)) => {
                        (k.clone(), json!({ "x": p[0], "y": p[1], "z": p[2], "rotation": v["rotation"] }))
                    }
                    _ => (k.clone(), poses_reshaped(v)),
                })
                .collect(),
        ),
        other => other.clone(),
    }
}

/// `now` without the [`ADDED`] keys that `golden` lacks, inside an
/// `error_estimate` of `call`, and without the [`ADDED_ANYWHERE`] keys it lacks.
fn without_added(call: &str, now: &Value, golden: &Value, in_estimate: bool) -> Value {
    match (now, golden) {
        (Value::Object(n), Value::Object(g)) => Value::Object(
            n.iter()
                .filter(|(k, _)| {
                    let added = |list: &[(&str, &str)]| list.iter().any(|(c, a)| call.starts_with(c) && a == k);
                    g.contains_key(*k) || !((in_estimate && added(ADDED)) || added(ADDED_ANYWHERE))
                })
                .map(|(k, v)| {
                    let w = g.get(k).unwrap_or(&Value::Null);
                    (k.clone(), without_added(call, v, w, in_estimate || k == "error_estimate"))
                })
                .collect(),
        ),
        (Value::Array(n), Value::Array(g)) if n.len() == g.len() => {
            Value::Array(n.iter().zip(g).map(|(v, w)| without_added(call, v, w, in_estimate)).collect())
        }
        _ => now.clone(),
    }
}

/// Reworded messages: (old words, new words).
const TEXTS: &[(&str, &str)] = &[("tendon --sweep: stopped at force =", "tendon --sweep: stopped at tension =")];

/// The golden `answer` of `call` in today's keys: [`RENAMES`] applied, and
/// `--limit`'s bare `stability_limit` or `stable_up_to` factor as the one
/// `stability_limit` object.
fn renamed(call: &str, answer: &Value) -> Value {
    match answer {
        Value::Object(map) => Value::Object(
            map.iter()
                .map(|(k, v)| {
                    let v = renamed(call, v);
                    let rule = RENAMES.iter().find(|(c, old, _)| call.starts_with(c) && old == k);
                    match (k.as_str(), v) {
                        ("stability_limit", Value::Number(x)) => (k.clone(), json!({ "factor": x, "status": "lost" })),
                        ("stable_up_to", Value::Number(x)) => {
                            ("stability_limit".into(), json!({ "factor": x, "status": "stable_up_to" }))
                        }
                        (_, v) => (rule.map_or(k.clone(), |r| r.2.to_string()), v),
                    }
                })
                .collect(),
        ),
        Value::Array(items) => Value::Array(items.iter().map(|v| renamed(call, v)).collect()),
        Value::String(text) => Value::String(TEXTS.iter().fold(text.clone(), |t, (old, new)| t.replace(old, new))),
        other => other.clone(),
    }
}

/// A golden entry `{call, status, answer}` in today's options and keys.
fn today(entry: &Value) -> Value {
    let mut call = entry["call"].as_str().unwrap_or_default().to_string();
    for (old, new) in CALLS {
        call = call.replacen(old, new, 1);
    }
    json!({ "call": call, "status": entry["status"], "answer": poses_reshaped(&reshaped(&renamed(&call, &entry["answer"]))) })
}

/// The calls: each example through the mechanism subcommands, then single
/// joints, then exports and the spatial joint. New calls go at the end: the
/// file's entries are compared in order.
fn calls() -> Vec<Vec<String>> {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples");
    let mut names: Vec<String> = std::fs::read_dir(root)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.file_name().to_string_lossy().into_owned()))
        .filter(|n| n.ends_with(".toml"))
        .collect();
    names.sort();
    // The spatial examples' calls come after every earlier call (below).
    let spatial = |n: &String| std::fs::read_to_string(format!("{root}/{n}")).unwrap().contains("dimension = 3");
    // Examples added after the file was written: their calls come last, after every earlier one.
    let (mut later, names): (Vec<String>, Vec<String>) = names.into_iter().partition(|n| LATER.contains(&n.as_str()));
    later.sort_by_key(|n| LATER.iter().position(|l| l == n));
    let (spatial_names, names): (Vec<String>, Vec<String>) = names.into_iter().partition(spatial);
    let mut out: Vec<Vec<String>> = Vec::new();
    let words = |s: &str| s.split_whitespace().map(String::from).collect::<Vec<_>>();
    // A planar (or later) example's calls: each mechanism subcommand on it.
    let example = |name: &String| {
        ["solve", "buckle", "modes --count 2", "simulate --duration 0.01 --every 0.005"].map(|rest| {
            let mut call = words(rest);
            call.insert(1, format!("{root}/{name}"));
            call
        })
    };
    out.extend(names.iter().flat_map(example));
    for call in [
        "kinematics --alpha 0.3,-0.2,0.1",
        "deflect --moment 1 --fy 0.5",
        "deflect --force 3.8477 --angle 45deg",
        "deflect --fx -3",
        "deflect --moment 1 --fx 0.5 --fy 0.3 --limit",
        "deflect --moment 0.5 --fy 1 --exact",
        "deflect --length 0.05 --modulus 200e9 --width 0.01 --thickness 4e-4,2e-4 --fy 0.5 --yield-strength 9e7 --shape 5",
        "deflect --ei 1,0.5 --moment 2 --order auto",
        "compliance",
        "compliance --exact",
        "buckling --tip free",
        "buckling --tip pinned",
        "buckling --tip clamped --order auto",
        "connect --pose 0.5,0.9,0.3",
        "connect --pose 0.5,0.9,0.3 --exact",
        "connect --pose 0.5,0.9,0.3 --segments 8",
        "tendon --tension 5 --root-offset 0.1 --tip-offset 0.05",
        "tendon --sweep 0:20:5 --root-offset 0.1 --tip-offset 0.1",
        "modes --mass-per-length 1 --count 4 --order 8 --exact",
        "modes --length 0.05 --modulus 200e9 --width 0.01 --thickness 2e-4 --density 7850 --tip-mass 0.005 --order 8 --count 2",
    ] {
        out.push(words(call));
    }
    // The export's fit report, with the MJCF itself as `model`, and a 3R
    // SDFormat export of a closed mechanism (its losses in `warnings`);
    // mixed_chain.toml has every rigid kind (pin, slider, weld).
    for (name, rest) in
        [("finger.toml", "--to mjcf"), ("four_bar.toml", "--to sdf --prb 3R"), ("mixed_chain.toml", "--to urdf")]
    {
        let mut call = vec!["export".to_string(), format!("{root}/{name}")];
        call.extend(words(rest));
        out.push(call);
    }
    for call in [
        "kinematics --spatial --order 2 --alpha 0.1,0.05,-0.2,0.1,0.3,-0.1",
        "deflect --spatial --length 0.05 --modulus 200e9 --width 0.01 --thickness 2e-4 --fy 0.2 --fz 0.05 --mx 1e-3",
        "compliance --spatial --ei 1,0.5 --gj 0.8",
    ] {
        out.push(words(call));
    }
    // The spatial mechanisms (`dimension = 3`).
    for name in &spatial_names {
        let file = format!("{root}/{name}");
        for rest in ["solve", "buckle", "modes --count 2"] {
            let mut call = words(rest);
            call.insert(1, file.clone());
            out.push(call);
        }
    }
    // The spatial mechanisms' motion (after every earlier call).
    for name in &spatial_names {
        out.push(vec![
            "simulate".into(),
            format!("{root}/{name}"),
            "--duration".into(),
            "0.01".into(),
            "--every".into(),
            "0.005".into(),
        ]);
    }
    out.extend(later.iter().flat_map(example));
    out
}

/// Examples added after the characterization was first written, in the order they came.
const LATER: [&str; 3] = ["right_angle_cantilever.toml", "grasp.toml", "grasp3d.toml"];

/// Each call's status and answer, in order.
fn answers() -> Vec<Value> {
    calls()
        .into_iter()
        .map(|mut call| {
            call.push("--json".into());
            let args: Vec<&str> = call.iter().map(String::as_str).collect();
            let (code, out, _) = run(&args);
            // Paths are the machine's; the example's name is kept.
            let shown = call.iter().map(|a| a.rsplit('/').next().unwrap_or(a)).collect::<Vec<_>>().join(" ");
            let answer = serde_json::from_str::<Value>(&out).unwrap_or(Value::String(out));
            json!({ "call": shown, "status": code, "answer": answer })
        })
        .collect()
}

/// Where `a` and `b` differ beyond the tolerance, if they do.
fn differ(a: &Value, b: &Value, at: &str) -> Option<String> {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) if x.is_f64() || y.is_f64() => {
            let (x, y) = (x.as_f64()?, y.as_f64()?);
            let ok = (x - y).abs() <= 1e-12 * x.abs().max(y.abs()) || (x - y).abs() <= 1e-14;
            (!ok).then(|| format!("{at}: {x:e} against {y:e}"))
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            x.iter().zip(y).enumerate().find_map(|(i, (x, y))| differ(x, y, &format!("{at}[{i}]")))
        }
        (Value::Object(x), Value::Object(y)) if x.len() == y.len() => x.iter().find_map(|(k, v)| match y.get(k) {
            Some(w) => differ(v, w, &format!("{at}.{k}")),
            None => Some(format!("{at}.{k}: missing from the golden file")),
        }),
        _ => (a != b).then(|| format!("{at}: {a} against {b}")),
    }
}

/// The golden file's `text` with the answers of the calls it lacks
/// appended: `now` must begin with its calls, in order (in today's
/// options), and its entries are kept byte for byte.
fn appended(text: &str, now: &[Value]) -> String {
    let golden: Vec<Value> = serde_json::from_str(text).unwrap();
    assert!(now.len() >= golden.len(), "calls were removed: regenerate all with scripts/characterize.sh --all");
    for (n, g) in now.iter().zip(&golden) {
        let kept = today(g);
        assert_eq!(n["call"], kept["call"], "a kept call changed: regenerate all with scripts/characterize.sh --all");
    }
    let new = &now[golden.len()..];
    if new.is_empty() {
        return text.to_string();
    }
    // A pretty-printed array's elements, as they sit inside the file's.
    let list = serde_json::to_string_pretty(new).unwrap();
    let inner = list.strip_prefix("[\n").and_then(|l| l.strip_suffix("\n]")).unwrap();
    let open = text.trim_end().strip_suffix(']').unwrap().trim_end();
    format!("{open},\n{inner}\n]\n")
}

#[test]
fn no_answer_changes() {
    let now = answers();
    if let Some(mode) = std::env::var_os("FLEXURE_BLESS") {
        std::fs::create_dir_all(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data")).unwrap();
        let text = match (mode.to_str(), std::fs::read_to_string(GOLDEN)) {
            (Some("new"), Ok(text)) => appended(&text, &now),
            (Some("all"), _) | (Some("new"), Err(_)) => serde_json::to_string_pretty(&now).unwrap() + "\n",
            (mode, _) => panic!("FLEXURE_BLESS={mode:?}: `new` (append new calls' answers) or `all`"),
        };
        std::fs::write(GOLDEN, text).unwrap();
        return;
    }
    let golden: Vec<Value> = serde_json::from_str(&std::fs::read_to_string(GOLDEN).unwrap()).unwrap();
    let golden: Vec<Value> = golden.iter().map(today).collect();
    assert_eq!(now.len(), golden.len(), "the calls changed: regenerate with scripts/characterize.sh");
    let changed: Vec<String> = now
        .iter()
        .zip(&golden)
        .filter_map(|(n, g)| {
            let call = n["call"].as_str().unwrap_or("?");
            let answer = without_added_top(call, &n["answer"], &g["answer"]);
            let now = json!({ "call": n["call"], "status": n["status"], "answer": answer });
            differ(&without_added(call, &now, g, false), g, call)
        })
        .collect();
    assert!(changed.is_empty(), "{} of {} answers changed:\n{}", changed.len(), now.len(), changed.join("\n"));
}
