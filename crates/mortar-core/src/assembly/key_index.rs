//! Where a key is in a short list that grows: the M blocks and master columns of one slave
//! face.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// A multiplicative hash of one `u32` key (the keys are face slots and node columns, not
/// chosen by an adversary): SipHash cost a fifth of the time of a coarse face against a
/// million partners.
#[derive(Debug, Clone, Copy, Default)]
struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_u32(&mut self, k: u32) {
        self.write_u64(u64::from(k));
    }

    fn write_u64(&mut self, k: u64) {
        // Fibonacci hashing, high half folded into the low bits the table indexes with.
        let h = (self.0 ^ k).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        self.0 = h ^ (h >> 32);
    }
}

/// Positions of keyed entries appended to a list: found by a linear search while the list
/// has at most [`KeyIndex::LINEAR`] entries (a slave face meets ~10 master faces), through a
/// map beyond (a coarse slave face against a million master faces made the search quadratic
/// in its partners). The map is built the first time the list outgrows the search, then kept
/// up to date by [`pushed`](KeyIndex::pushed).
#[derive(Debug, Clone, Default)]
pub(crate) struct KeyIndex {
    map: HashMap<u32, usize, BuildHasherDefault<KeyHasher>>,
}

impl KeyIndex {
    /// Entries searched linearly.
    pub const LINEAR: usize = 32;

    /// Forgets every key (the list was cleared).
    pub fn clear(&mut self) {
        self.map.clear();
    }

    /// The position of `key` in a list of `len` entries whose `i`-th key is `key_of(i)`.
    pub fn find(&mut self, len: usize, key_of: impl Fn(usize) -> u32, key: u32) -> Option<usize> {
        if len <= Self::LINEAR {
            return (0..len).find(|&i| key_of(i) == key);
        }
        self.find_in_map(len, key_of, key)
    }

    /// The position of `key` in `keys` (the list itself, so that the short search runs over
    /// a slice without bounds checks).
    #[inline]
    pub fn find_in(&mut self, keys: &[u32], key: u32) -> Option<usize> {
        if keys.len() <= Self::LINEAR {
            return keys.iter().position(|&k| k == key);
        }
        self.find_in_map(keys.len(), |i| keys[i], key)
    }

    /// The search through the map, built on first use.
    fn find_in_map(
        &mut self,
        len: usize,
        key_of: impl Fn(usize) -> u32,
        key: u32,
    ) -> Option<usize> {
        if self.map.is_empty() {
            self.map.extend((0..len).map(|i| (key_of(i), i)));
        }
        self.map.get(&key).copied()
    }

    /// Records that `key` was appended at `position`.
    pub fn pushed(&mut self, key: u32, position: usize) {
        if !self.map.is_empty() {
            self.map.insert(key, position);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Below and beyond the linear search, every key is found where it was pushed, and a
    /// missing one is not.
    #[test]
    fn finds_what_was_pushed_either_way() {
        let mut list: Vec<u32> = Vec::new();
        let mut index = KeyIndex::default();
        for k in 0..100u32 {
            let key = (k * 7919) % 1000;
            assert_eq!(index.find(list.len(), |i| list[i], key), None);
            list.push(key);
            index.pushed(key, list.len() - 1);
            for (i, &key) in list.iter().enumerate() {
                assert_eq!(index.find(list.len(), |j| list[j], key), Some(i));
            }
        }
        index.clear();
        list.clear();
        assert_eq!(index.find(0, |i| list[i], 7), None);
    }
}
