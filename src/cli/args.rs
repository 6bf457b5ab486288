//! Parsers for command-line and panel values: sizes, vectors, camera, on/off, and the names
//! of enum values ([`Named`], [`AutoOr`]), whose `--help` lists the names from the enum.

use std::ffi::OsStr;
use std::marker::PhantomData;

use clap::builder::{PossibleValue, TypedValueParser};

use bumpview::frame::{DEFAULT_PIXELS_PER_EDGE, MAX_DISPLACEMENT_LEVEL, MAX_PARALLAX_LAYERS};
use bumpview::names::{AUTO, Named, parse_or_auto};
use bumpview::state::{Command, SplitDifference};
use glam::Vec3;

pub use bumpview::render::export::parse_size;

/// `"X,Y"` → a pixel position, whole pixels from the top-left corner.
pub fn parse_pixel(text: &str) -> Result<[u32; 2], String> {
    let coordinate = |s: &str| s.trim().parse::<u32>().ok();
    match text.split_once(',').map(|(x, y)| (coordinate(x), coordinate(y))) {
        Some((Some(x), Some(y))) => Ok([x, y]),
        _ => Err(format!("{text:?}: expected X,Y in whole pixels, e.g. 400,300")),
    }
}

/// `"MIN,MAX"` → the parallax search's layers, each 1 to [`MAX_PARALLAX_LAYERS`]; one number
/// is a fixed count.
pub fn parse_layers(text: &str) -> Result<[u32; 2], String> {
    let count = |s: &str| s.trim().parse::<u32>().ok().filter(|n| (1..=MAX_PARALLAX_LAYERS).contains(n));
    let layers = match text.split_once(',') {
        Some((min, max)) => count(min).zip(count(max)).map(|(min, max)| [min, max]),
        None => count(text).map(|n| [n, n]),
    };
    layers.ok_or_else(|| format!("{text:?}: expected MIN,MAX layers, each 1 to {MAX_PARALLAX_LAYERS}, e.g. 8,32"))
}

/// `"a,b,c"` → three finite numbers.
pub fn parse_triple(text: &str) -> Result<[f32; 3], String> {
    let values: Vec<f32> = text
        .split(',')
        .map(|s| s.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("{text:?}: expected three numbers separated by commas"))?;
    match values[..] {
        [a, b, c] if values.iter().all(|v| v.is_finite()) => Ok([a, b, c]),
        _ => Err(format!("{text:?}: expected three finite numbers separated by commas")),
    }
}

pub fn parse_vec3(text: &str) -> Result<Vec3, String> {
    parse_triple(text).map(Vec3::from_array)
}

pub fn parse_on_off(text: &str) -> Result<bool, String> {
    match text {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err(format!("{text:?}: expected on or off")),
    }
}

/// The value named `text` ([`Named`]), else an error listing the names.
pub fn parse_named<T: Named>(text: &str) -> Result<T, String> {
    T::parse_name(text).map_err(|e| e.to_string())
}

/// A value of `T` or `auto` (each mesh's or material's own choice: `None`). A newtype because
/// clap reads a bare `Option<Option<T>>` as "a flag whose value may be missing".
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutoOr<T>(pub Option<T>);

/// clap's value parser for a [`Named`] enum: the value's name, listed in `--help` as the
/// flag's possible values (from the enum, so the help cannot go stale) and in the error for
/// any other text.
#[derive(Clone)]
pub struct NameParser<T>(PhantomData<T>);

/// [`NameParser`] for the flags that also take `auto` ([`AutoOr`]).
#[derive(Clone)]
pub struct NameOrAutoParser<T>(PhantomData<T>);

/// The value parser of a flag naming a `T`.
pub fn named<T>() -> NameParser<T> {
    NameParser(PhantomData)
}

/// The value parser of a flag naming a `T` or `auto`.
pub fn named_or_auto<T>() -> NameOrAutoParser<T> {
    NameOrAutoParser(PhantomData)
}

impl<T: Named + Send + Sync + 'static> TypedValueParser for NameParser<T> {
    type Value = T;

    fn parse_ref(&self, cmd: &clap::Command, arg: Option<&clap::Arg>, value: &OsStr) -> Result<T, clap::Error> {
        let text = value.to_string_lossy();
        T::parse_name(&text).map_err(|e| invalid_value(cmd, arg, &text, e))
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(T::names().into_iter().map(PossibleValue::new)))
    }
}

impl<T: Named + Send + Sync + 'static> TypedValueParser for NameOrAutoParser<T> {
    type Value = AutoOr<T>;

    fn parse_ref(&self, cmd: &clap::Command, arg: Option<&clap::Arg>, value: &OsStr) -> Result<AutoOr<T>, clap::Error> {
        let text = value.to_string_lossy();
        parse_or_auto(&text).map(AutoOr).map_err(|e| invalid_value(cmd, arg, &text, e))
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(std::iter::once(AUTO).chain(T::names()).map(PossibleValue::new)))
    }
}

/// clap's error for a bad value, on one line: the flag, the text and the names expected.
fn invalid_value(
    cmd: &clap::Command,
    arg: Option<&clap::Arg>,
    text: &str,
    reason: impl std::fmt::Display,
) -> clap::Error {
    let flag = arg.map_or_else(|| "the argument".to_owned(), |a| format!("'{a}'"));
    let message = format!("invalid value '{text}' for {flag}: {reason}\n");
    clap::Error::raw(clap::error::ErrorKind::ValueValidation, message).with_cmd(cmd)
}

/// `"LEFT,RIGHT"` → the command that sets the split view's pair for `difference`: two views,
/// strengths, modes, tangent methods, conventions (`opengl`, `directx`), bump sources,
/// parallax techniques, a parallax technique and a displacement level or `gpu` (`occlusion,6`), or
/// `uncompressed` and a texture format (`uncompressed,dds-bc5`).
pub fn parse_split_sides(difference: SplitDifference, text: &str) -> Result<Command, String> {
    let (left, right) = text
        .split_once(',')
        .map(|(l, r)| (l.trim(), r.trim()))
        .ok_or_else(|| format!("{text:?}: expected LEFT,RIGHT"))?;
    let sides = [left, right];
    Ok(match difference {
        SplitDifference::Bump => return Err("--split bump has fixed sides (off │ on)".into()),
        SplitDifference::View => Command::SetSplitViews(pair(sides, parse_named)?),
        SplitDifference::Strength => Command::SetSplitStrengths(pair(sides, parse_finite)?),
        SplitDifference::Mode => Command::SetSplitModes(pair(sides, parse_named)?),
        SplitDifference::Tangents => Command::SetSplitTangentMethods(pair(sides, parse_named)?),
        SplitDifference::Convention => Command::SetSplitConventions(pair(sides, parse_named)?),
        SplitDifference::BumpSource => Command::SetSplitBumpSources(pair(sides, parse_named)?),
        SplitDifference::Parallax => Command::SetSplitParallax(pair(sides, parse_named)?),
        SplitDifference::Mistake => Command::SetSplitMistakes(pair(sides, parse_named)?),
        SplitDifference::LightingSpace => Command::SetSplitLightingSpaces(pair(sides, parse_named)?),
        SplitDifference::MipFilter => Command::SetSplitMipFilters(pair(sides, parse_named)?),
        SplitDifference::DetailBlend => Command::SetSplitDetailBlends(pair(sides, parse_named)?),
        SplitDifference::Displacement => match parse_displacement(right)? {
            DisplacementArg::Gpu => Command::SetSplitDisplacement(parse_named(left)?, 1, Some(DEFAULT_PIXELS_PER_EDGE)),
            DisplacementArg::Level(0) => {
                return Err(format!("{right:?}: expected a displacement level, 1 to {MAX_DISPLACEMENT_LEVEL}, or gpu"));
            }
            DisplacementArg::Level(level) => Command::SetSplitDisplacement(parse_named(left)?, level, None),
        },
        SplitDifference::Compression if left == "uncompressed" => Command::SetSplitCompression(parse_named(right)?),
        SplitDifference::Compression => {
            return Err(format!("{left:?}: the compression split's left half is `uncompressed`"));
        }
    })
}

/// `--displacement`'s value: a CPU tessellation level, or `gpu`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DisplacementArg {
    Level(u32),
    Gpu,
}

/// `gpu` or a level, 0 to [`MAX_DISPLACEMENT_LEVEL`].
pub fn parse_displacement(text: &str) -> Result<DisplacementArg, String> {
    if text.trim() == "gpu" {
        return Ok(DisplacementArg::Gpu);
    }
    let level = text.trim().parse::<u32>().ok().filter(|l| *l <= MAX_DISPLACEMENT_LEVEL);
    level
        .map(DisplacementArg::Level)
        .ok_or_else(|| format!("{text:?}: expected gpu or a level, 0 to {MAX_DISPLACEMENT_LEVEL}"))
}

/// Both of `sides` parsed by `parse`.
fn pair<T>(sides: [&str; 2], parse: impl Fn(&str) -> Result<T, String>) -> Result<[T; 2], String> {
    Ok([parse(sides[0])?, parse(sides[1])?])
}

/// A finite number above zero.
pub fn parse_positive(text: &str) -> Result<f32, String> {
    text.trim()
        .parse::<f32>()
        .ok()
        .filter(|v| v.is_finite() && *v > 0.0)
        .ok_or_else(|| format!("{text:?}: expected a number above 0"))
}

pub fn parse_finite(text: &str) -> Result<f32, String> {
    text.trim()
        .parse::<f32>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| format!("{text:?}: expected a finite number"))
}

#[cfg(test)]
mod tests {
    use bumpview::scene::GreenAxis;
    use bumpview::tangent::TangentMethod;

    use super::*;

    #[test]
    fn parses_good_values_and_rejects_bad_ones() {
        assert_eq!(parse_size("1280x720"), Ok([1280, 720]));
        assert!(parse_size("0x720").is_err() && parse_size("big").is_err());
        assert_eq!(parse_vec3("1, -2,3.5"), Ok(Vec3::new(1.0, -2.0, 3.5)));
        assert!(parse_vec3("1,2").is_err() && parse_vec3("1,2,nan").is_err());
        assert!(parse_finite("inf").is_err());
        assert_eq!(parse_positive("0.02"), Ok(0.02));
        assert!(parse_positive("0").is_err() && parse_positive("-1").is_err() && parse_positive("nan").is_err());
        assert_eq!(parse_pixel("400, 300"), Ok([400, 300]));
        assert!(parse_pixel("400").is_err() && parse_pixel("-1,2").is_err());
    }

    #[test]
    fn split_sides_parse_by_the_difference() {
        let methods = parse_split_sides(SplitDifference::Tangents, "per-face, mikktspace");
        assert_eq!(methods, Ok(Command::SetSplitTangentMethods([TangentMethod::PerFace, TangentMethod::MikkTSpace])));
        let greens = parse_split_sides(SplitDifference::Convention, "directx,opengl");
        assert_eq!(greens, Ok(Command::SetSplitConventions([GreenAxis::DirectX, GreenAxis::OpenGl])));
        assert_eq!(parse_split_sides(SplitDifference::Strength, "0.5,2"), Ok(Command::SetSplitStrengths([0.5, 2.0])));
        assert!(parse_split_sides(SplitDifference::Bump, "off,on").is_err());
        assert!(parse_split_sides(SplitDifference::View, "lit").is_err());
        assert!(parse_split_sides(SplitDifference::Tangents, "mikktspace,bogus").unwrap_err().contains("per-face"));
    }
}
