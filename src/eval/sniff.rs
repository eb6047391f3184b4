//! Which ground-truth format a text looks like, for errors that say "this is a Caltech file,
//! not TuSimple" instead of only where the parser stopped.

use super::Format;
use serde_json::Value;

/// The format `text` looks like: a JSON object with `frames` (Caltech `labels.json`), JSON
/// lines with `raw_file` and `h_samples` (TuSimple) or with `frame` and `boundaries` (the
/// simulator's `gt.jsonl`, also what `lanepf track` writes), or lines of an even count of
/// numbers (CULane `.lines.txt`); `None` when it looks like none of them.
pub fn guess_format(text: &str) -> Option<Format> {
    if let Ok(Value::Object(o)) = serde_json::from_str::<Value>(text) {
        if o.get("frames").is_some_and(Value::is_array) {
            return Some(Format::Caltech);
        }
    }
    let first = text.lines().find(|l| !l.trim().is_empty())?;
    if let Ok(Value::Object(o)) = serde_json::from_str::<Value>(first) {
        if o.contains_key("raw_file") && o.contains_key("h_samples") {
            return Some(Format::Tusimple);
        }
        if o.contains_key("frame") && o.contains_key("boundaries") {
            return Some(Format::Synthetic);
        }
        return None;
    }
    let values: Vec<&str> = first.split_whitespace().collect();
    let numbers = values.iter().all(|v| v.parse::<f64>().is_ok());
    (numbers && values.len() % 2 == 0).then_some(Format::Culane)
}

/// What a file in `format` is, for a person.
pub fn describe(format: Format) -> &'static str {
    match format {
        Format::Caltech => "Caltech Lanes labels (a JSON object with `frames`)",
        Format::Tusimple => "TuSimple labels (JSON lines with `raw_file` and `h_samples`)",
        Format::Synthetic => {
            "lane estimates (JSON lines with `frame` and `boundaries`: a gt.jsonl or track output)"
        }
        Format::Culane => "CULane lane lines (x y pairs)",
        Format::KittiRoad => "KITTI road lane masks (*_lane_*.png)",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_format_is_recognised() {
        let caltech = r#"{"image_size": [640, 480], "frames": [{"frame": "f.png", "lanes": []}]}"#;
        assert_eq!(guess_format(caltech), Some(Format::Caltech));
        let caltech_pretty = "{\n  \"frames\": []\n}\n";
        assert_eq!(guess_format(caltech_pretty), Some(Format::Caltech));
        let tusimple = r#"{"lanes": [], "h_samples": [240], "raw_file": "clips/1/20.jpg"}"#;
        assert_eq!(guess_format(tusimple), Some(Format::Tusimple));
        let gt = "\n{\"frame\": \"f.png\", \"valid\": true, \"boundaries\": []}\n";
        assert_eq!(guess_format(gt), Some(Format::Synthetic));
        assert_eq!(guess_format("10 590 20.5 580 \n"), Some(Format::Culane));
        assert_eq!(guess_format("hello"), None);
        assert_eq!(guess_format("{\"x\": 1}"), None);
        assert_eq!(guess_format(""), None);
    }
}
