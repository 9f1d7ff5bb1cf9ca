//! The BLOCKS section: each block's base point and entities, for resolving INSERTs in the
//! extended mode. The model and paper space blocks are left out (their entities are the
//! ENTITIES section's).

use crate::entity::{read_entity, records, Ctx};
use crate::extra::{Block, ExtraReader};
use crate::tokens::{num, raw_str, Pair};
use crate::Drawing;

/// Malformed content goes to `d.extra_errors` (the reference never reads blocks).
pub(crate) fn read_blocks(ctx: &Ctx, pairs: &[Pair], d: &mut Drawing) {
    let mut current: Option<(String, Block)> = None;
    let mut extra = ExtraReader::default();
    for rec in records(pairs) {
        let kind = raw_str(rec[0].value);
        match &*kind {
            "BLOCK" => {
                let name = rec.iter().find(|p| p.code == 2).map(|p| ctx.text(p));
                let mut block = Block::default();
                for p in &rec[1..] {
                    let axis = match p.code {
                        10 => 0,
                        20 => 1,
                        30 => 2,
                        _ => continue,
                    };
                    match num(p) {
                        Ok(v) => block.base[axis] = v,
                        Err(e) => d.extra_errors.push(e),
                    }
                }
                current = name.filter(|n| !is_layout_block(n)).map(|n| (n, block));
            }
            "ENDBLK" => {
                if let Some((name, mut block)) = current.take() {
                    extra.finish(&mut block.extra);
                    d.blocks.insert(name, block);
                }
            }
            _ => {
                let Some((_, block)) = current.as_mut() else {
                    continue;
                };
                if extra.take(ctx, &kind, rec, &mut block.extra, &mut d.extra_errors) {
                    continue;
                }
                if matches!(&*kind, "LINE" | "ARC" | "CIRCLE" | "TEXT" | "MTEXT") {
                    match read_entity(ctx, &kind, rec) {
                        Ok(e) => block.entities.extend(e),
                        Err(e) => d.extra_errors.push(e),
                    }
                }
            }
        }
    }
}

/// `*Model_Space`, `*Paper_Space`, `*Paper_Space0`, … (any case; R12 writes `$MODEL_SPACE`).
fn is_layout_block(name: &str) -> bool {
    let n = name.to_ascii_uppercase();
    let n = n.trim_start_matches(['*', '$']);
    n.starts_with("MODEL_SPACE") || n.starts_with("PAPER_SPACE")
}
