//! The `[object]` table, read so that every error names its key.
//!
//! serde's internally tagged enums (`kind = "…"`) buffer a table before they
//! read the variant's fields, and the buffer forgets which key a value came
//! from: `width = "wide"` would be refused as `invalid type: string "wide",
//! expected f64` with no key. The table is read as a TOML table instead, its
//! `kind` taken out, and the variant's fields read from the rest one key at a
//! time, each error prefixed with its key: `` `width`: invalid type: string
//! "wide", expected f64 ``. Unknown and missing keys are named by serde as
//! before.

use std::path::PathBuf;

use serde::Deserialize;
use serde::de::value::{Error as TableError, MapDeserializer};
use serde::de::{self, Error as _, IntoDeserializer, Visitor};

use super::{Cuboid, ObjectShape, default_eggplant_flat};

/// The values of `kind`, as `ObjectShape`'s kebab-case variant names.
const KINDS: &[&str] = &["cuboid", "half-potato", "eggplant", "mesh"];

impl TryFrom<toml::Table> for ObjectShape {
    type Error = TableError;

    fn try_from(mut table: toml::Table) -> Result<Self, TableError> {
        let kind = match table.remove("kind") {
            Some(toml::Value::String(kind)) => kind,
            Some(other) => {
                return Err(TableError::custom(format!(
                    "`kind`: invalid type: {}, expected one of {}",
                    other.type_str(),
                    quoted(KINDS)
                )));
            }
            None => return Err(TableError::missing_field("kind")),
        };
        let fields = MapDeserializer::new(
            table
                .into_iter()
                .map(|(key, value)| (key.clone(), Keyed { key, value })),
        );
        match kind.as_str() {
            "cuboid" => Cuboid::deserialize(fields).map(ObjectShape::Cuboid),
            "half-potato" => HalfPotato::deserialize(fields).map(|h| ObjectShape::HalfPotato {
                length: h.length,
                width: h.width,
                height: h.height,
            }),
            "eggplant" => Eggplant::deserialize(fields).map(|e| ObjectShape::Eggplant {
                length: e.length,
                diameter: e.diameter,
                flat: e.flat,
            }),
            "mesh" => Mesh::deserialize(fields).map(|m| ObjectShape::Mesh { path: m.path }),
            _ => Err(TableError::custom(format!(
                "`kind`: unknown variant `{kind}`, expected one of {}",
                quoted(KINDS)
            ))),
        }
    }
}

/// `` `a`, `b`, `c` ``.
fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|name| format!("`{name}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The keys of `kind = "half-potato"` (documented on [`ObjectShape::HalfPotato`]).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct HalfPotato {
    length: f64,
    width: f64,
    height: f64,
}

/// The keys of `kind = "eggplant"` (documented on [`ObjectShape::Eggplant`]).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Eggplant {
    length: f64,
    diameter: f64,
    #[serde(default = "default_eggplant_flat")]
    flat: f64,
}

/// The keys of `kind = "mesh"` (documented on [`ObjectShape::Mesh`]).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Mesh {
    path: PathBuf,
}

/// One value of the table with the key it was written under.
struct Keyed {
    key: String,
    value: toml::Value,
}

impl Keyed {
    /// `result` with its error prefixed by the key.
    fn named<T>(key: &str, result: Result<T, toml::de::Error>) -> Result<T, TableError> {
        result.map_err(|e| TableError::custom(format!("`{key}`: {}", e.message())))
    }
}

impl IntoDeserializer<'_, TableError> for Keyed {
    type Deserializer = Self;

    fn into_deserializer(self) -> Self {
        self
    }
}

impl<'de> de::Deserializer<'de> for Keyed {
    type Error = TableError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, TableError> {
        Self::named(&self.key, self.value.deserialize_any(visitor))
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, TableError> {
        Self::named(&self.key, self.value.deserialize_option(visitor))
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        visitor: V,
    ) -> Result<V::Value, TableError> {
        Self::named(
            &self.key,
            self.value.deserialize_newtype_struct(name, visitor),
        )
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, TableError> {
        Self::named(
            &self.key,
            self.value.deserialize_enum(name, variants, visitor),
        )
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
        bytes byte_buf unit unit_struct seq tuple tuple_struct map struct
        identifier ignored_any
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<ObjectShape, String> {
        #[derive(Debug, Deserialize)]
        struct File {
            #[allow(dead_code)]
            object: ObjectShape,
        }
        toml::from_str::<File>(text)
            .map(|f| f.object)
            .map_err(|e| e.message().to_string())
    }

    #[test]
    fn every_kind_reads_as_the_enum_writes_it() {
        let shapes = [
            ObjectShape::Cuboid(Cuboid {
                width: 0.03,
                height: 0.025,
                length: 0.04,
            }),
            ObjectShape::HalfPotato {
                length: 0.09,
                width: 0.06,
                height: 0.035,
            },
            ObjectShape::Eggplant {
                length: 0.2,
                diameter: 0.07,
                flat: 0.005,
            },
            ObjectShape::Mesh {
                path: "meshes/potato.obj".into(),
            },
        ];
        for shape in shapes {
            #[derive(serde::Serialize)]
            struct File<'a> {
                object: &'a ObjectShape,
            }
            let text = toml::to_string(&File { object: &shape }).unwrap();
            assert_eq!(read(&text), Ok(shape), "{text}");
        }
        let egg = read("[object]\nkind = \"eggplant\"\nlength = 0.2\ndiameter = 0.07\n");
        assert!(matches!(egg, Ok(ObjectShape::Eggplant { flat, .. }) if flat == 0.004));
        let whole = read("[object]\nkind = \"cuboid\"\nwidth = 1\nheight = 1\nlength = 1\n");
        assert!(whole.is_ok(), "an integer is a number: {whole:?}");
    }

    #[test]
    fn a_value_of_the_wrong_type_is_named_by_its_key() {
        let text =
            "[object]\nkind = \"half-potato\"\nlength = 0.09\nwidth = \"wide\"\nheight = 0.035\n";
        assert_eq!(
            read(text).unwrap_err(),
            "`width`: invalid type: string \"wide\", expected f64"
        );
        let text = "[object]\nkind = \"mesh\"\npath = 3\n";
        let e = read(text).unwrap_err();
        assert!(e.starts_with("`path`: invalid type: integer `3`"), "{e}");
    }

    #[test]
    fn kind_and_unknown_or_missing_keys_are_named() {
        let e = read("[object]\nkind = \"halfpotato\"\n").unwrap_err();
        assert_eq!(
            e,
            "`kind`: unknown variant `halfpotato`, expected one of `cuboid`, `half-potato`, `eggplant`, `mesh`"
        );
        let e = read("[object]\nkind = 1\n").unwrap_err();
        assert!(e.starts_with("`kind`: invalid type: integer"), "{e}");
        let e = read("[object]\nwidth = 0.1\n").unwrap_err();
        assert_eq!(e, "missing field `kind`");
        let e = read("[object]\nkind = \"cuboid\"\nwidht = 0.1\nheight = 0.1\nlength = 0.1\n")
            .unwrap_err();
        assert!(
            e.starts_with("unknown field `widht`, expected one of"),
            "{e}"
        );
        let e = read("[object]\nkind = \"eggplant\"\nlength = 0.2\n").unwrap_err();
        assert_eq!(e, "missing field `diameter`");
    }
}
