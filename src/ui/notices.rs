//! Messages the user must see (warnings, errors, the guard's line, recording and reload
//! status): the newest is a notice over the view, near the top, for a few seconds (an error
//! longer); every one stays listed in the Log window.

use imgui::{Condition, Ui};
use std::time::{Duration, Instant};

/// How long a notice stays over the view.
const NOTICE: Duration = Duration::from_secs(6);
const ERROR_NOTICE: Duration = Duration::from_secs(15);
/// Messages kept in the log (the oldest go first).
const LOG_KEEP: usize = 200;

#[derive(Debug, Clone, PartialEq)]
struct Entry {
    text: String,
    error: bool,
    /// When it last came (a message repeated in a row is one entry, counted).
    at: Instant,
    count: u32,
}

#[derive(Debug, Clone, Default)]
pub struct Notices {
    entries: Vec<Entry>,
    pub show_log: bool,
}

impl Notices {
    /// Adds a message; the same one again in a row counts up and shows anew.
    pub fn push(&mut self, text: &str, error: bool) {
        let now = Instant::now();
        match self.entries.last_mut() {
            Some(last) if last.text == text && last.error == error => {
                last.count += 1;
                last.at = now;
            }
            _ => {
                self.entries.push(Entry { text: text.to_string(), error, at: now, count: 1 });
                if self.entries.len() > LOG_KEEP {
                    self.entries.remove(0);
                }
            }
        }
    }

    /// The newest message: (text, error).
    pub fn last(&self) -> Option<(&str, bool)> {
        self.entries.last().map(|e| (e.text.as_str(), e.error))
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The message shown over the view at `now`, if one is: (text, error).
    pub fn current(&self, now: Instant) -> Option<(&str, bool)> {
        let last = self.entries.last()?;
        let keep = if last.error { ERROR_NOTICE } else { NOTICE };
        (now.duration_since(last.at) < keep).then(|| self.last()).flatten()
    }

    /// Draws the notice over the free part of the view (`free`: x0, y0, x1, y1 in pixels) and,
    /// when open, the Log window.
    pub fn draw(&mut self, ui: &Ui, free: [f32; 4]) {
        if let Some((text, error)) = self.current(Instant::now()) {
            // On the foreground draw list: over every window, never taking input.
            let width = (free[2] - free[0] - 40.0).clamp(200.0, 640.0);
            let lines = wrap(text, width - 20.0, |t| ui.calc_text_size(t)[0]);
            let line_height = ui.text_line_height_with_spacing();
            let x = (free[0] + free[2] - width) * 0.5;
            let y = free[1] + 36.0; // below the recording indicator's row
            let draw = ui.get_foreground_draw_list();
            let bottom = y + 12.0 + line_height * lines.len() as f32;
            let edge = if error { [0.9, 0.3, 0.25, 1.0] } else { [0.35, 0.7, 0.35, 1.0] };
            draw.add_rect([x, y], [x + width, bottom], [0.06, 0.06, 0.07, 0.92])
                .filled(true)
                .rounding(5.0)
                .build();
            draw.add_rect([x, y], [x + width, bottom], edge).rounding(5.0).thickness(1.5).build();
            let colour = if error { [1.0, 0.6, 0.55, 1.0] } else { [0.75, 0.95, 0.75, 1.0] };
            for (k, line) in lines.iter().enumerate() {
                draw.add_text([x + 10.0, y + 6.0 + line_height * k as f32], colour, line);
            }
        }
        if !self.show_log {
            return;
        }
        let mut open = true;
        ui.window("Log")
            .opened(&mut open)
            .position([free[0] + 20.0, free[3] - 260.0], Condition::FirstUseEver)
            .size([560.0, 240.0], Condition::FirstUseEver)
            .build(|| {
                if self.entries.is_empty() {
                    ui.text_disabled("no messages yet");
                }
                for e in self.entries.iter().rev() {
                    let colour = if e.error { [1.0, 0.5, 0.45, 1.0] } else { [0.8, 0.8, 0.8, 1.0] };
                    let _c = ui.push_style_color(imgui::StyleColor::Text, colour);
                    let repeat = if e.count > 1 { format!(" (x{})", e.count) } else { String::new() };
                    ui.text_wrapped(format!("{}{repeat}", e.text));
                }
            });
        self.show_log = open;
    }
}

/// Splits `text` into lines no wider than `width` by `measure`, at spaces (a word wider than
/// a line stays whole on its own).
fn wrap(text: &str, width: f32, measure: impl Fn(&str) -> f32) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let candidate = if line.is_empty() { word.to_string() } else { format!("{line} {word}") };
        if !line.is_empty() && measure(&candidate) > width {
            lines.push(std::mem::replace(&mut line, word.to_string()));
        } else {
            line = candidate;
        }
    }
    lines.push(line);
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A notice shows for a while (an error longer), a repeat counts up and shows anew, and the
    /// log keeps the last LOG_KEEP messages.
    #[test]
    fn notices_show_for_a_while_and_stay_in_the_log() {
        let mut n = Notices::default();
        n.push("saved a.toml", false);
        let t = n.entries[0].at;
        assert_eq!(n.current(t), Some(("saved a.toml", false)));
        assert_eq!(n.current(t + NOTICE), None);
        n.push("cloth ran away", true);
        let t = n.entries[1].at;
        assert!(n.current(t + NOTICE).is_some() && n.current(t + ERROR_NOTICE).is_none());
        n.push("cloth ran away", true);
        assert_eq!((n.len(), n.entries[1].count), (2, 2));
        for k in 0..LOG_KEEP + 5 {
            n.push(&format!("m{k}"), false);
        }
        assert_eq!(n.len(), LOG_KEEP);
        assert_eq!(n.entries.last().unwrap().text, format!("m{}", LOG_KEEP + 4));
    }

    #[test]
    fn wrapping_keeps_words_whole_and_lines_within_the_width() {
        let measure = |t: &str| t.len() as f32;
        assert_eq!(wrap("aa bb cc dd", 5.0, measure), ["aa bb", "cc dd"]);
        assert_eq!(wrap("a verylongword b", 5.0, measure), ["a", "verylongword", "b"]);
        assert_eq!(wrap("", 5.0, measure), [""]);
    }
}
