//! Names of enum values as the command line, presets, reports and the panel spell them
//! (`shading-normal`, `per-face`, `sobel3`). Each named enum derives them once with strum:
//! `IntoStaticStr` gives a value's name (`#[strum(serialize_all = "kebab-case")]`, or
//! `#[strum(serialize = "…")]` on a variant whose name is not its kebab-case spelling) and
//! `VariantArray` every value in declaration order. [`Named`] reads both, so no enum keeps a
//! hand-written name table and every lookup lists the same names.

/// An enum whose values have fixed names: every enum deriving strum's `IntoStaticStr` and
/// `VariantArray`.
pub trait Named: Copy + PartialEq + strum::VariantArray + Into<&'static str> {
    /// The value's name.
    fn name(self) -> &'static str {
        self.into()
    }

    /// Every value, in declaration order (the order of the panel, `--help` and reports).
    fn all() -> &'static [Self] {
        Self::VARIANTS
    }

    /// Every value's name, in [`Named::all`]'s order.
    fn names() -> Vec<&'static str> {
        Self::VARIANTS.iter().map(|&value| value.name()).collect()
    }

    /// The value named `name`, if there is one.
    fn from_name(name: &str) -> Option<Self> {
        Self::VARIANTS.iter().copied().find(|&value| value.name() == name)
    }

    /// The value named `text`, else an error that lists the names.
    fn parse_name(text: &str) -> Result<Self, UnknownName> {
        Self::from_name(text).ok_or_else(|| UnknownName { text: text.to_owned(), expected: Self::names() })
    }
}

impl<T: Copy + PartialEq + strum::VariantArray + Into<&'static str>> Named for T {}

/// The name of an optional value, `auto` for `None` (a tangent method or shading model left
/// to each mesh or material).
pub fn name_or_auto<T: Named>(value: Option<T>) -> &'static str {
    value.map_or(AUTO, Named::name)
}

/// `auto` (`None`) or a value's name; the error lists `auto` and the names.
pub fn parse_or_auto<T: Named>(text: &str) -> Result<Option<T>, UnknownName> {
    if text == AUTO {
        return Ok(None);
    }
    T::parse_name(text).map(Some).map_err(|mut error| {
        error.expected.insert(0, AUTO);
        error
    })
}

/// The name of "each mesh's or material's own choice".
pub const AUTO: &str = "auto";

/// A name that is none of an enum's values: the text given and the names it could have been.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{text:?}: expected one of {}", expected.join(", "))]
pub struct UnknownName {
    pub text: String,
    pub expected: Vec<&'static str>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Clone, Copy, PartialEq, strum::IntoStaticStr, strum::VariantArray)]
    #[strum(serialize_all = "kebab-case")]
    enum Fruit {
        GreenApple,
        #[strum(serialize = "pear")]
        Conference,
    }

    #[test]
    fn names_come_from_the_derive_and_lookups_list_them() {
        assert_eq!(Fruit::names(), ["green-apple", "pear"]);
        assert_eq!(Fruit::from_name("pear"), Some(Fruit::Conference));
        assert_eq!(Fruit::from_name("Conference"), None);
        let error = Fruit::parse_name("plum").unwrap_err();
        assert_eq!(error.to_string(), "\"plum\": expected one of green-apple, pear");
        assert_eq!(parse_or_auto::<Fruit>("auto"), Ok(None));
        assert_eq!(parse_or_auto::<Fruit>("pear"), Ok(Some(Fruit::Conference)));
        let error = parse_or_auto::<Fruit>("plum").unwrap_err();
        assert_eq!(error.to_string(), "\"plum\": expected one of auto, green-apple, pear");
        assert_eq!(name_or_auto(Some(Fruit::GreenApple)), "green-apple");
        assert_eq!(name_or_auto::<Fruit>(None), "auto");
    }
}
