//! Statistics: lengths, times and command count (reference-output.md §14).

use crate::diag::Lang;
use crate::emit::{Item, Kind};

#[derive(Debug, Clone, Default, PartialEq)]
pub struct Stats {
    pub mill: f64,
    pub mill_min: f64,
    pub drill: f64,
    pub drill_min: f64,
    pub sweep: f64,
    pub sweep_min: f64,
    pub count: usize,
}

const TICKS_PER_MINUTE: f64 = 600_000_000.0;

impl Stats {
    pub fn of(items: &[Item], sweep_speed: f64) -> Stats {
        let mut s = Stats::default();
        for it in items {
            match it.kind {
                Kind::Mill => {
                    s.mill += it.len;
                    s.mill_min += it.len / it.feed;
                }
                Kind::Drill => {
                    s.drill += it.len;
                    s.drill_min += it.len / it.feed;
                }
                Kind::HSweep | Kind::VSweep => {
                    s.sweep += it.len;
                    s.sweep_min += it.len / sweep_speed;
                }
                Kind::Comment => continue,
            }
            s.count += 1;
        }
        s.mill_min *= 1.4;
        s.drill_min *= 1.4;
        s.sweep_min *= 1.4;
        s
    }

    /// The five statistics texts, e.g. `Fräslänge:     115 mm   ca.  2 min`.
    pub fn lines(&self, lang: Lang) -> [String; 5] {
        let labels = match lang {
            Lang::En => [
                "Milling length:",
                "Drill length:",
                "Sweeps:",
                "Sum:",
                "Command count:",
            ],
            Lang::De => [
                "Fräslänge:",
                "Bohrungen:",
                "Leerfahrten:",
                "Summe:",
                "Befehlszahl:",
            ],
        };
        let ticks = |m: f64| (m * TICKS_PER_MINUTE).trunc();
        let (tm, td, ts) = (
            ticks(self.mill_min),
            ticks(self.drill_min),
            ticks(self.sweep_min),
        );
        let minutes = |t: f64| (t / TICKS_PER_MINUTE).ceil();
        let line = |l: &str, len: f64, t: f64| {
            format!("{l:<12} {:>5.0} mm   ca.{:>3.0} min", len, minutes(t))
        };
        [
            line(labels[0], self.mill, tm),
            line(labels[1], self.drill, td),
            line(labels[2], self.sweep, ts),
            line(labels[3], self.mill + self.drill + self.sweep, tm + td + ts),
            format!("{:<12} {}", labels[4], self.count),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_lines() {
        let s = Stats {
            mill: 115.374,
            mill_min: 115.374 / 150.0 * 1.4,
            drill: 3.5,
            drill_min: 3.5 / 150.0 * 1.4,
            sweep: 65.99,
            sweep_min: 65.99 / 500.0 * 1.4,
            count: 8,
        };
        let de = s.lines(Lang::De);
        assert_eq!(de[0], "Fräslänge:     115 mm   ca.  2 min");
        assert_eq!(de[4], "Befehlszahl: 8");
        let en = s.lines(Lang::En);
        assert_eq!(en[0], "Milling length:   115 mm   ca.  2 min");
        assert_eq!(en[1], "Drill length:     4 mm   ca.  1 min");
        assert_eq!(en[3], "Sum:           185 mm   ca.  2 min");
        assert_eq!(
            Stats::default().lines(Lang::De)[1],
            "Bohrungen:       0 mm   ca.  0 min"
        );
    }
}
