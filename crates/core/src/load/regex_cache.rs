//! One compile of each regular expression per process. Every file of a `check` run and every
//! analysis of the language server uses the same few patterns (path and file names,
//! restrictions); compiling them again per file cost more than reading the file.

use regex::Regex;
use std::collections::HashMap;
use std::hash::Hash;
use std::sync::{Arc, Mutex, OnceLock};

/// Entries kept at most: an editor typing a pattern makes a new one per keystroke.
const CAPACITY: usize = 256;

/// A small process-wide memo table; cleared when full (patterns are cheap to rebuild).
pub struct Memo<K, V> {
    map: Mutex<HashMap<K, Arc<OnceLock<V>>>>,
    capacity: usize,
}

impl<K: Eq + Hash + Clone, V: Clone> Memo<K, V> {
    pub fn new() -> Self {
        Self::with_capacity(CAPACITY)
    }
    pub fn with_capacity(capacity: usize) -> Self {
        Memo {
            map: Mutex::new(HashMap::new()),
            capacity: capacity.max(1),
        }
    }
    /// The value for `key`, made by `make` the first time. Made outside the table's lock
    /// (compiling a regex can take a while) but once per key: the parallel workers of
    /// `check` asking for the same key at the same moment wait for the one that makes it.
    pub fn get_or(&self, key: &K, make: impl FnOnce() -> V) -> V {
        let cell = {
            let mut map = self.lock();
            if !map.contains_key(key) && map.len() >= self.capacity {
                map.clear();
            }
            map.entry(key.clone()).or_default().clone()
        };
        cell.get_or_init(make).clone()
    }
    /// Drops the entry of `key` (those holding its value keep it).
    pub fn forget(&self, key: &K) {
        self.lock().remove(key);
    }
    fn lock(&self) -> std::sync::MutexGuard<'_, HashMap<K, Arc<OnceLock<V>>>> {
        // a panic elsewhere while holding the lock leaves a usable map
        self.map.lock().unwrap_or_else(|e| e.into_inner())
    }
}

impl<K: Eq + Hash + Clone, V: Clone> Default for Memo<K, V> {
    fn default() -> Self {
        Self::new()
    }
}

/// The compiled form of `pattern`, shared.
pub fn regex(pattern: &str) -> Result<Arc<Regex>, regex::Error> {
    static MEMO: OnceLock<Memo<String, Result<Arc<Regex>, regex::Error>>> = OnceLock::new();
    MEMO.get_or_init(Memo::new)
        .get_or(&pattern.to_string(), || Regex::new(pattern).map(Arc::new))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_same_pattern_is_compiled_once() {
        let a = regex("^a+b$").unwrap();
        let b = regex("^a+b$").unwrap();
        assert!(Arc::ptr_eq(&a, &b));
        assert!(a.is_match("aab"));
        assert!(regex("(").is_err());
    }

    #[test]
    fn a_full_table_starts_again() {
        let memo: Memo<usize, usize> = Memo::new();
        for i in 0..CAPACITY * 3 {
            assert_eq!(memo.get_or(&i, || i * 2), i * 2);
        }
        assert!(memo.lock().len() <= CAPACITY);
    }
}
