//! Where receivers and point forces may sit: the closed rectangle `0 <= x <= width`,
//! `0 <= z <= depth` (m). The line of an absorbing side is the solid's last node line
//! (its field is the physical one there); the layers outside it are not.

/// The rectangle of a 2D problem.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Region {
    lo: [f64; 2],
    hi: [f64; 2],
    /// A mesh's bounding box (else the rectangle).
    mesh: bool,
}

impl Region {
    /// The region of a `width` x `depth` rectangle, m.
    pub fn new(width: f64, depth: f64) -> Self {
        Region {
            lo: [0.0; 2],
            hi: [width, depth],
            mesh: false,
        }
    }

    /// The bounding box `[lo, hi]` (m) of a mesh (whether a point is in the mesh itself is
    /// found when the plan locates it).
    pub fn bounds(lo: [f64; 2], hi: [f64; 2]) -> Self {
        Region { lo, hi, mesh: true }
    }

    /// Whether `p = [x, z]` (m) is in the region.
    pub fn contains(&self, p: [f64; 2]) -> bool {
        (self.lo[0]..=self.hi[0]).contains(&p[0]) && (self.lo[1]..=self.hi[1]).contains(&p[1])
    }

    /// The region in words, for an error's allowed range.
    pub fn describe(&self) -> String {
        if self.mesh {
            return format!(
                "inside the mesh, whose bounding box is {} <= x <= {} m and {} <= z <= {} m",
                self.lo[0], self.hi[0], self.lo[1], self.hi[1]
            );
        }
        let (width, depth) = (self.hi[0], self.hi[1]);
        format!(
            "inside the rectangle, 0 <= x <= {} m and 0 <= z <= {} m (not in an absorbing \
             layer outside it)",
            width, depth
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_region_is_the_closed_rectangle() {
        let r = Region::new(2.0, 1.0);
        for p in [[0.0, 0.0], [2.0, 1.0], [1.0, 0.5]] {
            assert!(r.contains(p), "{p:?}");
        }
        for p in [
            [-0.1, 0.5],
            [2.1, 0.5],
            [1.0, 1.01],
            [1.0, -0.1],
            [f64::NAN, 0.5],
        ] {
            assert!(!r.contains(p), "{p:?}");
        }
        assert!(r.describe().contains("0 <= x <= 2 m and 0 <= z <= 1 m"));
    }
}
